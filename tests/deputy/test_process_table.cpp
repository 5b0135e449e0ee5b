// The deputy's process table: orders to actions, exits, respawn back-off, stop escalation.
#include <gtest/gtest.h>

#include "procman/process_table.h"

using namespace slide::procman;

namespace {

DesiredCommand desired(const std::string& id, int32_t runid, bool force_quit = false, bool respawn = false) {
  DesiredCommand d;
  d.spec.id = id;
  d.spec.exec = "sleep 10";
  d.spec.auto_respawn = respawn;
  d.spec.stop_signal = 15;
  d.spec.stop_time_allowed = 2;
  d.desired_runid = runid;
  d.force_quit = force_quit;
  return d;
}

constexpr int64_t kS = 1000000;

}  // namespace

TEST(ProcessTable, StartsWhenRunIdDiffersAndOnlyOnce) {
  ProcessTable t;
  bool changed = false;
  auto a = t.applyOrders({desired("x", 1)}, 0, &changed);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].kind, Action::kStart);
  EXPECT_TRUE(changed);
  t.markStarted("x", 100, 0);
  EXPECT_EQ(t.commands().at("x").actual_runid, 1);
  EXPECT_TRUE(t.applyOrders({desired("x", 1)}, kS, &changed).empty());
  EXPECT_FALSE(changed);
}

TEST(ProcessTable, CreatedStoppedCommandDoesNotStart) {
  ProcessTable t;
  EXPECT_TRUE(t.applyOrders({desired("x", 0)}, 0, nullptr).empty());
  EXPECT_TRUE(t.applyOrders({desired("x", 3, true)}, 0, nullptr).empty());
  EXPECT_EQ(t.commands().at("x").actual_runid, 3);  // adopted: nothing left to do
}

TEST(ProcessTable, StopSendsStopSignalThenSigkillAfterAllowedTime) {
  ProcessTable t;
  t.applyOrders({desired("x", 1)}, 0, nullptr);
  t.markStarted("x", 100, 0);
  auto a = t.applyOrders({desired("x", 1, true)}, kS, nullptr);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].kind, Action::kSignal);
  EXPECT_EQ(a[0].signal, 15);
  EXPECT_TRUE(t.applyOrders({desired("x", 1, true)}, kS + 1, nullptr).empty());  // no second signal
  EXPECT_TRUE(t.tick(2 * kS).empty());
  a = t.tick(3 * kS + 1);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].signal, SIGKILL);
  EXPECT_TRUE(t.tick(4 * kS).empty());
  const ExitOutcome out = t.markExited(100, SIGKILL, 4 * kS);
  EXPECT_TRUE(out.known);
  EXPECT_TRUE(out.actions.empty());
  EXPECT_EQ(t.commands().at("x").pid, 0);
}

TEST(ProcessTable, RestartStopsThenStartsWithNewRunId) {
  ProcessTable t;
  t.applyOrders({desired("x", 1)}, 0, nullptr);
  t.markStarted("x", 100, 0);
  auto a = t.applyOrders({desired("x", 2)}, kS, nullptr);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].kind, Action::kSignal);
  const ExitOutcome out = t.markExited(100, 15, kS);
  ASSERT_EQ(out.actions.size(), 1u);
  EXPECT_EQ(out.actions[0].kind, Action::kStart);
  t.markStarted("x", 101, kS);
  EXPECT_EQ(t.commands().at("x").actual_runid, 2);
}

TEST(ProcessTable, RespawnBackOffGrowsWhileCrashing) {
  ProcessTable t(BackoffParams{100, 800, 10000});
  t.applyOrders({desired("x", 1, false, true)}, 0, nullptr);
  int64_t now = 0;
  std::vector<int64_t> delays;
  for (int pid = 100; pid < 106; ++pid) {
    t.markStarted("x", pid, now);
    now += 10000;  // crashes after 10 ms
    t.markExited(pid, 1 << 8, now);
    const int64_t due = t.commands().at("x").respawn_at_us;
    ASSERT_GT(due, now);
    delays.push_back((due - now) / 1000);
    EXPECT_TRUE(t.tick(due - 1).empty());
    auto a = t.tick(due);
    ASSERT_EQ(a.size(), 1u);
    EXPECT_EQ(a[0].kind, Action::kStart);
    now = due;
  }
  EXPECT_EQ(delays, (std::vector<int64_t>{100, 200, 400, 800, 800, 800}));
  // A long run resets the delay.
  t.markStarted("x", 200, now);
  t.markExited(200, 0, now + 20 * kS);
  EXPECT_EQ(t.commands().at("x").respawn_at_us - (now + 20 * kS), 100 * 1000);
}

TEST(ProcessTable, NoRespawnWithoutAutoRespawnOrWhenStopped) {
  ProcessTable t;
  t.applyOrders({desired("x", 1)}, 0, nullptr);
  t.markStarted("x", 100, 0);
  t.markExited(100, 0, kS);
  EXPECT_EQ(t.commands().at("x").respawn_at_us, 0);
  EXPECT_TRUE(t.tick(100 * kS).empty());
  ProcessTable r;
  r.applyOrders({desired("y", 1, false, true)}, 0, nullptr);
  r.markStarted("y", 100, 0);
  r.applyOrders({desired("y", 1, true, true)}, kS, nullptr);
  r.markExited(100, 15, kS);
  EXPECT_TRUE(r.tick(100 * kS).empty());
}

TEST(ProcessTable, CommandsMissingFromOrdersAreStoppedAndRemoved) {
  ProcessTable t;
  t.applyOrders({desired("x", 1), desired("y", 0)}, 0, nullptr);
  t.markStarted("x", 100, 0);
  bool changed = false;
  auto a = t.applyOrders({}, kS, &changed);
  EXPECT_TRUE(changed);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].kind, Action::kSignal);
  EXPECT_EQ(t.commands().count("y"), 0u);  // not running: dropped at once
  ASSERT_EQ(t.commands().count("x"), 1u);  // running: dropped when it exits
  EXPECT_TRUE(t.markExited(100, 15, kS).removed);
  EXPECT_TRUE(t.commands().empty());
}

TEST(ProcessTable, UpdatesSpecAndStopAllCapsWait) {
  ProcessTable t;
  t.applyOrders({desired("x", 1)}, 0, nullptr);
  t.markStarted("x", 100, 0);
  DesiredCommand d = desired("x", 1);
  d.spec.exec = "sleep 20";
  d.spec.group = "g";
  bool changed = false;
  EXPECT_TRUE(t.applyOrders({d}, kS, &changed).empty());
  EXPECT_TRUE(changed);
  EXPECT_EQ(t.commands().at("x").spec.exec, "sleep 20");
  auto a = t.stopAll(2 * kS, 0.5);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].signal, 15);
  EXPECT_EQ(t.tick(2 * kS + 600000).at(0).signal, SIGKILL);
  EXPECT_TRUE(t.anyRunning());
}

TEST(ProcessTable, StaleOrders) {
  EXPECT_FALSE(ordersAreStale(0, 59 * kS));
  EXPECT_TRUE(ordersAreStale(0, 61 * kS));
}
