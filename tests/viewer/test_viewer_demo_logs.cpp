// What ./slide demo records is what a viewer replaying the run draws: each robot's lcm-logger
// (tools/commands/lib/team_run.sh, the team.pmd it writes) keeps every robot-bus channel the
// viewer listens to, the last scan's instances as the segmenter's thinned INSTANCES_PREVIEW,
// and neither the full INSTANCES (~100 KB a scan) nor the raw scans.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "app/channels.h"
#include "viewer_node.h"

using namespace slide;
namespace fs = std::filesystem;

TEST(ViewerDemoLogs, EachRobotsLoggerKeepsEveryChannelTheViewerDraws) {
  const fs::path dir = fs::path(SLIDE_BINARY_DIR) / "tests/viewer/demo_logs";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string cmd = "cd " + std::string(SLIDE_SOURCE_DIR) + " && SLIDE_ROOT=$PWD SLIDE_BIN=" +
                          std::string(SLIDE_BINARY_DIR) + "/bin bash -c 'source tools/commands/lib/team_run.sh && " +
                          "team_run_write_config " + dir.string() + " " + (dir / "data").string() + " 2 1' > " +
                          (dir / "write.log").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "team_run_write_config failed: " << (dir / "write.log");
  std::ifstream in(dir / "team.pmd");
  std::stringstream pmd;
  pmd << in.rdbuf();
  const std::string text = pmd.str();
  const std::regex logger(R"re(cmd "logger-(\d)" \{ exec = "lcm-logger [^"]*-c \(([^)]*)\) [^"]*robot\1\.lcmlog")re");
  int loggers = 0;
  const ViewerChannels ch;
  EXPECT_EQ(ch.instances, app::channels::kInstancesPreview);  // the segmenter's default preview channel
  for (std::sregex_iterator it(text.begin(), text.end(), logger), end; it != end; ++it) {
    ++loggers;
    const std::regex recorded("(" + (*it)[2].str() + ")");  // LCM matches a channel whole, as regex_match
    for (const std::string& c : ch.robotBus()) EXPECT_TRUE(std::regex_match(c, recorded)) << c << " not recorded";
    for (const char* c : {app::channels::kInstances, app::channels::kScan, app::channels::kRgbd})
      EXPECT_FALSE(std::regex_match(std::string(c), recorded)) << c << " recorded";
  }
  EXPECT_EQ(loggers, 2) << text;
  EXPECT_EQ(text.find("--preview-channel"), std::string::npos) << "the demo's segmenters keep their preview";
  fs::remove_all(dir);
}
