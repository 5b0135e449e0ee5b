// ./slide run-bag's generated procman config (tools/commands/run-bag.sh, write_run_pmd) keeps
// every driver argument one word through the .pmd string and procman's exec split: paths with
// spaces, quotes and backslashes reach the daemons unchanged.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "procman/exec_args.h"
#include "procman/pmd_config.h"

namespace fs = std::filesystem;
using namespace slide::procman;

namespace {
std::vector<std::string> argvOf(const PmdConfig& c, const std::string& id) {
  for (const PmdCommand& cmd : c.commands)
    if (cmd.spec.id == id) return splitExec(cmd.spec.exec).argv;
  ADD_FAILURE() << "no command " << id;
  return {};
}
}  // namespace

TEST(RunBagPmd, ArgumentsWithSpacesAndQuotesStayOneWordEach) {
  const fs::path dir = fs::temp_directory_path() / ("slide run bag pmd " + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string bag = (dir / "my \"best\" bag's.bag").string(), out = (dir / "out dir").string();
  // The shell's own quoting of the test's arguments: single quotes, ' written as '\''.
  auto sh = [](const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  const std::string src = SLIDE_SOURCE_DIR, pmd = (dir / "run.pmd").string();
  const std::string cmd = "SLIDE_ROOT=" + sh(src) + " bash -c 'source \"$SLIDE_ROOT/tools/commands/lib/common.sh\"; source "
                          "\"$SLIDE_ROOT/tools/commands/run-bag.sh\"; write_run_pmd \"$@\"' _ " + sh(pmd) + " " + sh(bag) + " " +
                          sh(out) + " 2 --config " + sh(dir.string() + "/a b\\c.yaml") + " --cloud-topic /points";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const PmdConfig c = loadPmd(pmd);
  EXPECT_EQ(argvOf(c, "driver"),
            (std::vector<std::string>{"slide-sensor-driver", bag, "--robot", "0", "--lcm-url", "udpm://239.255.76.67:7670?ttl=0&recv_buf_size=4194304",
                                      "--rate", "2", "--no-progress", "--config", dir.string() + "/a b\\c.yaml",
                                      "--cloud-topic", "/points"}));
  EXPECT_EQ(argvOf(c, "logger"), (std::vector<std::string>{"lcm-logger", "-f",
                                                           "--lcm-url=udpm://239.255.76.67:7670?ttl=0&recv_buf_size=4194304",
                                                           out + "/logs/robot0.lcmlog"}));
  const std::vector<std::string> opt = argvOf(c, "optimizer");
  ASSERT_FALSE(opt.empty());
  EXPECT_EQ(opt.back(), out + "/out");
  EXPECT_NE(c.findScript("start"), nullptr);
  EXPECT_NE(c.findScript("stop"), nullptr);
  fs::remove_all(dir);
}
