// The sheriff's model and script runner, driven with made-up deputy reports.
#include <gtest/gtest.h>

#include <algorithm>

#include "procman/script_runner.h"
#include "procman/status_table.h"

using namespace slide::procman;

namespace {

const char* kConfig = R"(
group "g" {
  cmd "a" { exec = "x"; deputy = "d1"; }
  cmd "b" { exec = "y"; deputy = "d2"; auto_respawn = "true"; }
}
cmd "c" { exec = "z"; deputy = "d1"; }
script "up" { start group "g" wait "running"; wait ms 100; }
script "down" { stop everything wait "stopped"; }
script "both" { run_script "up"; run_script "down"; }
script "loop" { run_script "loop2"; }
script "loop2" { run_script "loop"; }
script "ghost" { start cmd "nope"; }
)";

constexpr int64_t kMs = 1000;

// A fake deputy: obeys the model's orders at once, like a real one would after a message.
void obey(SheriffModel& m, const std::string& deputy, int& next_pid, bool crash = false) {
  std::vector<CommandReport> reports;
  for (const DesiredCommand& d : m.ordersFor(deputy)) {
    CommandReport r;
    r.spec = d.spec;
    const auto& cmds = m.commands();
    const auto it = std::find_if(cmds.begin(), cmds.end(), [&](const SheriffCommand& c) { return c.spec.id == d.spec.id; });
    const CommandReport& old = it->report;
    r.actual_runid = d.desired_runid;
    if (d.force_quit) {
      r.pid = 0;
      r.exit_code = old.pid ? 15 : old.exit_code;
    } else if (crash) {
      r.pid = 0;
      r.exit_code = 1 << 8;
    } else {
      r.pid = (old.pid && old.actual_runid == d.desired_runid) ? old.pid : next_pid++;
    }
    reports.push_back(r);
  }
  m.onDeputyInfo(deputy, reports);
}

}  // namespace

TEST(ScriptRunner, RunsNestedScriptsToTheEnd) {
  const PmdConfig cfg = parsePmd(kConfig, "t.pmd");
  SheriffModel model(cfg.commands);
  int pid = 100;
  model.onDeputyInfo("d1", {});
  model.onDeputyInfo("d2", {});
  ScriptRunner r(cfg, model, "both", 5.0);
  bool changed = false;
  int64_t now = 0;
  EXPECT_EQ(r.step(now, &changed), ScriptRunner::Result::kRunning);
  EXPECT_TRUE(changed);
  EXPECT_EQ(model.state(0), CommandState::kUnknown);  // ordered, not yet held by its deputy
  EXPECT_EQ(model.ordersFor("d1").at(0).desired_runid, 1);
  obey(model, "d1", pid);
  obey(model, "d2", pid);
  EXPECT_EQ(model.state(0), CommandState::kRunning);
  EXPECT_EQ(r.step(now += 10 * kMs, &changed), ScriptRunner::Result::kRunning);  // wait ms 100
  EXPECT_EQ(r.step(now += 100 * kMs, &changed), ScriptRunner::Result::kRunning);  // stop sent
  EXPECT_TRUE(model.commands()[2].force_quit);
  obey(model, "d1", pid);
  obey(model, "d2", pid);
  EXPECT_EQ(r.step(now += 10 * kMs, &changed), ScriptRunner::Result::kDone);
  EXPECT_EQ(model.state(0), CommandState::kStoppedOk);
  const std::string table = formatStatusTable(model);
  EXPECT_NE(table.find("stopped (ok)"), std::string::npos) << table;
}

TEST(ScriptRunner, FailsFastWhenACommandExits) {
  const PmdConfig cfg = parsePmd(kConfig, "t.pmd");
  SheriffModel model(cfg.commands);
  int pid = 100;
  ScriptRunner r(cfg, model, "up", 5.0);
  EXPECT_EQ(r.step(0, nullptr), ScriptRunner::Result::kRunning);
  obey(model, "d1", pid, true);
  obey(model, "d2", pid);
  EXPECT_EQ(r.step(1000, nullptr), ScriptRunner::Result::kFailed);
  ASSERT_EQ(r.failures().size(), 1u);
  EXPECT_NE(r.failures()[0].find("d1/a exited (status 1)"), std::string::npos) << r.failures()[0];
}

TEST(ScriptRunner, TimesOutWhenADeputyIsSilent) {
  const PmdConfig cfg = parsePmd(kConfig, "t.pmd");
  SheriffModel model(cfg.commands);
  int pid = 100;
  ScriptRunner r(cfg, model, "up", 2.0);
  EXPECT_EQ(r.step(0, nullptr), ScriptRunner::Result::kRunning);
  obey(model, "d1", pid);  // d2 never answers
  EXPECT_EQ(r.step(1000 * kMs, nullptr), ScriptRunner::Result::kRunning);
  EXPECT_EQ(r.step(2001 * kMs, nullptr), ScriptRunner::Result::kFailed);
  ASSERT_EQ(r.failures().size(), 1u);
  EXPECT_NE(r.failures()[0].find("d2/b is unknown"), std::string::npos) << r.failures()[0];
}

TEST(ScriptRunner, RejectsUnknownNamesAndRecursion) {
  const PmdConfig cfg = parsePmd(kConfig, "t.pmd");
  SheriffModel model(cfg.commands);
  EXPECT_THROW(ScriptRunner(cfg, model, "missing", 1.0), PmdError);
  EXPECT_THROW(ScriptRunner(cfg, model, "loop", 1.0), PmdError);
  try {
    ScriptRunner(cfg, model, "ghost", 1.0);
    FAIL();
  } catch (const PmdError& e) {
    EXPECT_EQ(std::string(e.what()), "t.pmd:12:18: no command named 'nope'");
  }
}

TEST(SheriffModel, ACommandTheDeputyNeverReportsStaysUnknown) {
  // A deputy that rejects our orders (e.g. a type mismatch) never lists the command: a stop
  // must not look done, and a script waiting for "stopped" must fail.
  const PmdConfig cfg = parsePmd(kConfig, "t.pmd");
  SheriffModel model(cfg.commands);
  model.stop(0);
  for (int i = 0; i < 3; ++i) model.onDeputyInfo("d1", {});
  EXPECT_EQ(model.state(0), CommandState::kUnknown);
  ScriptRunner r(cfg, model, "down", 0.5);
  ScriptRunner::Result res = ScriptRunner::Result::kRunning;
  for (int64_t t = 0; t <= 2000 * kMs && res == ScriptRunner::Result::kRunning; t += 100 * kMs) {
    model.onDeputyInfo("d1", {});
    model.onDeputyInfo("d2", {});
    res = r.step(t, nullptr);
  }
  EXPECT_EQ(res, ScriptRunner::Result::kFailed);
  ASSERT_FALSE(r.failures().empty());
  EXPECT_NE(r.failures()[0].find("is unknown"), std::string::npos) << r.failures()[0];
}

TEST(SheriffModel, AdoptsRunningCommandsWithoutRestart) {
  const PmdConfig cfg = parsePmd(kConfig, "t.pmd");
  SheriffModel model(cfg.commands);
  model.onDeputyInfo("d1", {});  // not there yet: its state is unknown, not "stopped"
  EXPECT_EQ(model.state(0), CommandState::kUnknown);
  CommandReport a;
  a.spec = cfg.commands[0].spec;
  a.pid = 42;
  a.actual_runid = 7;
  model.onDeputyInfo("d1", {a});
  EXPECT_EQ(model.state(0), CommandState::kRunning);
  EXPECT_EQ(model.ordersFor("d1").at(0).desired_runid, 7);
  model.start(0);  // already running: nothing changes
  EXPECT_EQ(model.ordersFor("d1").at(0).desired_runid, 7);
  model.restart(0);
  EXPECT_EQ(model.ordersFor("d1").at(0).desired_runid, 8);
  EXPECT_EQ(model.state(0), CommandState::kRestarting);
  EXPECT_EQ(model.select(TargetKind::kGroup, "g").size(), 2u);
  EXPECT_EQ(model.select(TargetKind::kGroup, "g/").size(), 2u);
  EXPECT_EQ(model.select(TargetKind::kGroup, "x").size(), 0u);
}
