// slide-sheriff against a real slide-deputy in a private network namespace: a script that
// brings commands up and down exits 0 and its table shows them; a command that exits for
// good makes the script fail with exit code 1.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <memory>

#include "deputy_harness.h"
#include "netns.h"

using namespace slide::test;

namespace {

const char* kConfig = R"(
group "g" {
    cmd "sleeper" { exec = "sleep 30"; deputy = "s1"; stop_signal = 15; }
    cmd "crasher" { exec = "sh -c 'exit 4'"; deputy = "s1"; }
}
script "up" { start cmd "sleeper" wait "running"; }
script "cycle" { run_script "up"; restart group "g/" ; wait ms 200; stop cmd "crasher"; stop everything wait "stopped"; }
script "bad" { start cmd "crasher" wait "running"; }
)";

// Runs slide-sheriff; returns (exit status, stdout).
std::pair<int, std::string> sheriff(const std::string& cfg, const std::string& script) {
  const std::string cmd = std::string(SLIDE_BINARY_DIR) + "/bin/slide-sheriff -c " + cfg + " -s " + script +
                          " --wait-timeout 5 --deputy-timeout 5 --log-level warn --lcm-url '" + kTestUrl + "'";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 512> buf;
  while (fgets(buf.data(), buf.size(), p)) out += buf.data();
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

}  // namespace

TEST(SheriffLcm, RunsScriptsAndReportsFailure) {
  const std::string why = enterPrivateNetns();
  if (!why.empty()) GTEST_SKIP() << "needs a private network namespace: " << why;
  const std::string cfg = testing::TempDir() + "sheriff_test.pmd";
  std::ofstream(cfg) << kConfig;
  const pid_t deputy = startDeputy("s1");
  SheriffStub probe;
  ASSERT_TRUE(probe.waitFor([](const auto& i) { return i.deputy_id == "s1"; }, 5.0));

  auto [rc, out] = sheriff(cfg, "up");
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("sleeper  g      running"), std::string::npos) << out;

  std::tie(rc, out) = sheriff(cfg, "cycle");
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("sleeper  g      stopped (ok)"), std::string::npos) << out;

  std::tie(rc, out) = sheriff(cfg, "bad");
  EXPECT_EQ(rc, 1) << out;
  EXPECT_NE(out.find("crasher  g      stopped (error)"), std::string::npos) << out;

  std::tie(rc, out) = sheriff(cfg, "nosuch");
  EXPECT_EQ(rc, 1) << out;

  kill(deputy, SIGTERM);
  EXPECT_GE(waitExit(deputy, 6.0), 0);
}
