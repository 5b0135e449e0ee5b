// slide-deputy as a subprocess, driven through procman LCM messages inside a private network
// namespace: start, stop (with SIGKILL escalation), restart, respawn, output, removal, stale
// and foreign orders, id conflicts, and clean shutdown.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/time.h>
#include <sys/wait.h>

#include <chrono>
#include <fstream>
#include <sstream>

#include "deputy_harness.h"
#include "netns.h"

using namespace slide::test;
using slide::procman::DesiredCommand;

namespace {

bool alive(int pid) { return pid > 0 && kill(pid, 0) == 0; }

class DeputyLcm : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string why = enterPrivateNetns();
    if (!why.empty()) GTEST_SKIP() << "needs a private network namespace: " << why;
    stub_ = std::make_unique<SheriffStub>();
    deputy_ = startDeputy("t1");
    ASSERT_TRUE(stub_->waitFor([](const auto& i) { return i.deputy_id == "t1"; }, 5.0)) << "no PM_INFO from the deputy";
  }
  void TearDown() override {
    if (deputy_ <= 0) return;
    kill(deputy_, SIGTERM);
    const int st = waitExit(deputy_, 6.0);
    EXPECT_TRUE(st >= 0 && WIFEXITED(st) && WEXITSTATUS(st) == 0) << "deputy exit status " << st;
    if (st < 0) kill(deputy_, SIGKILL), waitExit(deputy_, 2.0);
  }
  // Waits until command id runs with the given run id; returns its pid (0 on timeout).
  int waitRunning(const std::string& id, int32_t runid, int not_pid = 0) {
    int pid = 0;
    stub_->waitFor([&](const auto& i) {
      const auto* c = findCommand(i, id);
      if (c && c->pid > 0 && c->actual_runid == runid && c->pid != not_pid) pid = c->pid;
      return pid > 0;
    }, 5.0);
    return pid;
  }
  std::unique_ptr<SheriffStub> stub_;
  pid_t deputy_ = -1;
};

}  // namespace

TEST_F(DeputyLcm, StartsRestartsAndStops) {
  stub_->order("t1", {command("x", "sleep 30", 1)});
  const int pid1 = waitRunning("x", 1);
  ASSERT_GT(pid1, 0);
  EXPECT_TRUE(alive(pid1));
  EXPECT_EQ(findCommand(stub_->info, "x")->cmd.group, "test");

  stub_->order("t1", {command("x", "sleep 30", 2)});  // restart
  const int pid2 = waitRunning("x", 2, pid1);
  ASSERT_GT(pid2, 0);
  EXPECT_FALSE(alive(pid1));

  stub_->order("t1", {command("x", "sleep 30", 2, true)});  // stop
  ASSERT_TRUE(stub_->waitFor([](const auto& i) { const auto* c = findCommand(i, "x"); return c && c->pid == 0; }, 5.0));
  const int st = findCommand(stub_->info, "x")->exit_code;
  EXPECT_TRUE(WIFSIGNALED(st) && WTERMSIG(st) == SIGTERM) << st;
  EXPECT_FALSE(alive(pid2));
}

TEST_F(DeputyLcm, StopEscalatesToSigkillAfterStopTimeAllowed) {
  stub_->order("t1", {command("x", "sh -c 'trap \"\" TERM; while true; do sleep 0.1; done'", 1)});
  ASSERT_GT(waitRunning("x", 1), 0);
  stub_->spin(0.3);
  const auto t0 = std::chrono::steady_clock::now();
  stub_->order("t1", {command("x", "sh -c 'trap \"\" TERM; while true; do sleep 0.1; done'", 1, true)});
  ASSERT_TRUE(stub_->waitFor([](const auto& i) { const auto* c = findCommand(i, "x"); return c && c->pid == 0; }, 5.0));
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const int st = findCommand(stub_->info, "x")->exit_code;
  EXPECT_TRUE(WIFSIGNALED(st) && WTERMSIG(st) == SIGKILL) << st;
  EXPECT_GE(waited, 0.9);  // stop_time_allowed is 1 s
}

TEST_F(DeputyLcm, RespawnsAKilledCommand) {
  stub_->order("t1", {command("x", "sleep 30", 1, false, true)});
  int pid = waitRunning("x", 1);
  ASSERT_GT(pid, 0);
  for (int round = 0; round < 2; ++round) {
    kill(pid, SIGKILL);
    const int next = waitRunning("x", 1, pid);
    ASSERT_GT(next, 0) << "not respawned in round " << round;
    EXPECT_NE(next, pid);
    pid = next;
  }
  // Without auto_respawn a killed command stays down.
  stub_->order("t1", {command("x", "sleep 30", 1, false, false)});
  stub_->spin(0.3);
  kill(pid, SIGKILL);
  ASSERT_TRUE(stub_->waitFor([](const auto& i) { const auto* c = findCommand(i, "x"); return c && c->pid == 0; }, 5.0));
  stub_->spin(1.0);
  EXPECT_EQ(findCommand(stub_->info, "x")->pid, 0);
}

TEST_F(DeputyLcm, ForwardsOutputAndReportsFigures) {
  stub_->order("t1", {command("talk", "sh -c 'echo hello-from-child; echo err-line >&2; sleep 30'", 1)});
  ASSERT_GT(waitRunning("talk", 1), 0);
  stub_->spin(2.2);  // two CPU/memory samples
  EXPECT_NE(stub_->output.find("talk: hello-from-child"), std::string::npos) << stub_->output;
  EXPECT_NE(stub_->output.find("err-line"), std::string::npos) << stub_->output;
  const auto& i = stub_->info;
  EXPECT_GT(i.phys_mem_total_bytes, 0);
  EXPECT_GE(i.cpu_load, 0.f);
  EXPECT_LE(i.cpu_load, 1.f);
  EXPECT_GT(findCommand(i, "talk")->mem_rss_bytes, 0);
  EXPECT_GT(findCommand(i, "talk")->mem_vsize_bytes, 0);
}

TEST_F(DeputyLcm, RemovesCommandsMissingFromOrders) {
  stub_->order("t1", {command("x", "sleep 30", 1), command("y", "sleep 30", 1)});
  const int px = waitRunning("x", 1);
  ASSERT_GT(px, 0);
  ASSERT_GT(waitRunning("y", 1), 0);
  stub_->order("t1", {command("y", "sleep 30", 1)});
  ASSERT_TRUE(stub_->waitFor([](const auto& i) { return i.ncmds == 1 && findCommand(i, "y"); }, 5.0));
  EXPECT_FALSE(alive(px));
}

TEST_F(DeputyLcm, IgnoresStaleAndForeignOrders) {
  stub_->order("t1", {command("x", "sleep 30", 1)}, -120'000'000);  // two minutes old
  stub_->spin(1.5);
  EXPECT_EQ(stub_->info.ncmds, 0);
  EXPECT_NE(stub_->output.find("stale"), std::string::npos);
  stub_->order("someone-else", {command("x", "sleep 30", 1)});
  stub_->spin(1.5);
  EXPECT_EQ(stub_->info.ncmds, 0);
}

TEST_F(DeputyLcm, SecondDeputyWithSameIdExits) {
  const pid_t dup = startDeputy("t1");
  const int st = waitExit(dup, 5.0);
  ASSERT_GE(st, 0) << "the duplicate deputy kept running";
  kill(dup, SIGKILL);
  EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 2) << st;
}

TEST_F(DeputyLcm, SigtermStopsAllChildren) {
  stub_->order("t1", {command("x", "sleep 30", 1), command("y", "sh -c 'trap \"\" TERM; sleep 30'", 1)});
  const int px = waitRunning("x", 1), py = waitRunning("y", 1);
  ASSERT_GT(px, 0);
  ASSERT_GT(py, 0);
  kill(deputy_, SIGTERM);
  const int st = waitExit(deputy_, 6.0);
  deputy_ = -1;
  EXPECT_TRUE(st >= 0 && WIFEXITED(st) && WEXITSTATUS(st) == 0) << st;
  EXPECT_FALSE(alive(px));
  EXPECT_FALSE(alive(py));
}

// Orders exactly as procman's sheriff encodes them (bytes made by procman's own types, see
// fixtures/procman_lcm/README.md) start a command on slide-deputy.
TEST(DeputyProcmanWire, ProcmanEncodedOrdersStartACommand) {
  const std::string why = enterPrivateNetns();
  if (!why.empty()) GTEST_SKIP() << "needs a private network namespace: " << why;
  std::ifstream in(std::string(SLIDE_SOURCE_DIR) + "/tests/deputy/fixtures/procman_lcm/pm_orders_start_hello.hex");
  ASSERT_TRUE(in.good());
  std::string hex, line;
  while (std::getline(in, line)) hex += line;
  std::vector<uint8_t> bytes;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) bytes.push_back(uint8_t(std::stoi(hex.substr(i, 2), nullptr, 16)));
  ASSERT_GT(bytes.size(), 16u);

  SheriffStub stub;  // receives PM_INFO / PM_OUTPUT; sends nothing of its own
  const pid_t deputy = startDeputy("robot1");
  lcm::LCM raw(kTestUrl);
  ASSERT_TRUE(raw.good());
  bool started = false;
  for (int i = 0; i < 20 && !started; ++i) {
    timeval tv;
    gettimeofday(&tv, nullptr);
    const uint64_t now = uint64_t(tv.tv_sec) * 1000000 + uint64_t(tv.tv_usec);
    for (int b = 0; b < 8; ++b) bytes[8 + b] = uint8_t(now >> (56 - 8 * b));  // utime, big-endian
    raw.publish("PM_ORDERS", bytes.data(), static_cast<unsigned>(bytes.size()));
    stub.spin(0.5);
    const auto* c = stub.have_info ? findCommand(stub.info, "hello") : nullptr;
    started = c && c->actual_runid == 1 && stub.output.find("hello-from-procman") != std::string::npos;
  }
  EXPECT_TRUE(started) << "output: " << stub.output;
  kill(deputy, SIGTERM);
  if (waitExit(deputy, 6.0) < 0) kill(deputy, SIGKILL), waitExit(deputy, 2.0);
}
