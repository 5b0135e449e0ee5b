// The .pmd config language: a full config, and errors that name line and column.
#include <gtest/gtest.h>

#include "procman/pmd_config.h"

using namespace slide::procman;

namespace {

const char* kConfig = R"(# team
group "robot1" {
    cmd "driver" {
        exec = "slide-sensor-driver --robot 1";
        deputy = "robot1";
        auto_respawn = "true";
        stop_signal = 15;
        stop_time_allowed = 3;
    }
    group "back" {
        cmd "opt" { exec = "slide-optimizer"; host = "robot1"; }
    }
}
cmd "top" { exec = "sleep 1"; deputy = "base"; }
script "up" {
    start group "robot1" wait "running";
    wait ms 250;
    wait cmd "top" status "stopped";
    restart cmd "opt";
    stop everything wait "stopped";
    run_script "other";
}
script "other" { start everything; }
)";

// Parses text expected to fail; returns "line:column: message" without the file name.
std::string errorOf(const std::string& text) {
  try {
    parsePmd(text, "t.pmd");
  } catch (const PmdError& e) {
    const std::string w = e.what();
    EXPECT_EQ(w.rfind("t.pmd:", 0), 0u) << w;
    return w.substr(6);
  }
  ADD_FAILURE() << "no error for: " << text;
  return "";
}

}  // namespace

TEST(PmdConfig, ParsesGroupsCommandsAndScripts) {
  const PmdConfig c = parsePmd(kConfig, "team.pmd");
  ASSERT_EQ(c.commands.size(), 3u);
  const PmdCommand& d = c.commands[0];
  EXPECT_EQ(d.spec.id, "driver");
  EXPECT_EQ(d.spec.group, "robot1");
  EXPECT_EQ(d.deputy, "robot1");
  EXPECT_TRUE(d.spec.auto_respawn);
  EXPECT_EQ(d.spec.stop_signal, 15);
  EXPECT_DOUBLE_EQ(d.spec.stop_time_allowed, 3.0);
  EXPECT_EQ(d.pos.line, 3);
  EXPECT_EQ(c.commands[1].spec.group, "robot1/back");
  EXPECT_EQ(c.commands[1].deputy, "robot1");
  EXPECT_FALSE(c.commands[1].spec.auto_respawn);
  EXPECT_EQ(c.commands[1].spec.stop_signal, SIGINT);
  EXPECT_EQ(c.commands[2].spec.group, "");
  ASSERT_EQ(c.scripts.size(), 2u);
  const PmdScript* up = c.findScript("up");
  ASSERT_NE(up, nullptr);
  ASSERT_EQ(up->actions.size(), 6u);
  EXPECT_EQ(up->actions[0].kind, ScriptAction::kStart);
  EXPECT_EQ(up->actions[0].target, TargetKind::kGroup);
  EXPECT_EQ(up->actions[0].wait, WaitStatus::kRunning);
  EXPECT_EQ(up->actions[1].kind, ScriptAction::kWaitMs);
  EXPECT_EQ(up->actions[1].ms, 250);
  EXPECT_EQ(up->actions[2].kind, ScriptAction::kWaitStatus);
  EXPECT_EQ(up->actions[2].wait, WaitStatus::kStopped);
  EXPECT_EQ(up->actions[3].kind, ScriptAction::kRestart);
  EXPECT_EQ(up->actions[4].target, TargetKind::kEverything);
  EXPECT_EQ(up->actions[5].kind, ScriptAction::kRunScript);
  EXPECT_EQ(up->actions[5].pos.line, 21);
  EXPECT_EQ(up->actions[5].pos.column, 5);
}

TEST(PmdConfig, ErrorsNameLineAndColumn) {
  EXPECT_EQ(errorOf("cmd \"a\" {\n  exec = \"x\"\n  deputy = \"d\"; }"), "3:3: expected ';', found identifier 'deputy'");
  EXPECT_EQ(errorOf("cmd \"a\" { exec = \"x\"; color = \"red\"; deputy = \"d\"; }").substr(0, 36),
            "1:23: unknown command attribute 'col");
  EXPECT_EQ(errorOf("cmd \"a\" { deputy = \"d\"; }"), "1:25: command 'a' has no exec");
  EXPECT_EQ(errorOf("cmd \"a\" { exec = \"x\"; }"), "1:23: command 'a' has no deputy");
  EXPECT_EQ(errorOf("group \"g\" {\n  cmd \"a\" { exec = \"x; deputy = \"d\"; }\n}"), "2:35: unterminated string");
  EXPECT_EQ(errorOf("\n\n   @"), "3:4: invalid character '@'");
  EXPECT_EQ(errorOf("script \"s\" { start cmd \"a\" wait \"sleeping\"; }"),
            "1:33: expected \"running\" or \"stopped\", found \"sleeping\"");
  EXPECT_EQ(errorOf("script \"s\" { jump everything; }"), "1:14: expected start, stop, restart, wait or run_script, found 'jump'");
  EXPECT_EQ(errorOf("script \"s\" { wait ms; }"), "1:21: expected a number of milliseconds, found ';'");
  EXPECT_EQ(errorOf("cmd \"a\" { exec = \"x\"; deputy = \"d\"; stop_signal = 0; }"),
            "1:51: stop_signal must be a signal number 1..64");
  EXPECT_EQ(errorOf("cmd \"a\" { exec = \"x\"; deputy = \"d\"; auto_respawn = \"yes\"; }"),
            "1:52: auto_respawn must be \"true\" or \"false\"");
  EXPECT_EQ(errorOf("group \"a/b\" { }"), "1:7: '/' is not allowed in a group name");
  EXPECT_EQ(errorOf("group \"g\" {\n"), "2:1: expected '}', 'cmd' or 'group', found end of file");
  EXPECT_EQ(errorOf("script \"s\" { }\nscript \"s\" { }"), "2:8: script 's' defined twice");
  EXPECT_EQ(errorOf("cmd \"a\" { exec = \"x\"; deputy = \"d\"; }\ncmd \"a\" { exec = \"y\"; deputy = \"d\"; }"),
            "2:1: command 'a' defined twice for deputy 'd'");
  EXPECT_EQ(errorOf("cmd \"a\" { exec = \"x\"; exec = \"y\"; deputy = \"d\"; }"), "1:23: attribute 'exec' given twice");
}

TEST(PmdConfig, MissingFileIsAnError) {
  EXPECT_THROW(loadPmd("/nonexistent/x.pmd"), PmdError);
}
