// The page in real browsers, Debian's Chromium (headless) and Firefox ESR (a window on a private
// Xvfb display: headless Firefox has no WebGL), both driven by puppeteer-core from the page's npm
// packages (daemons/viewer/web/launch_browser.mjs), against slide-viewer following a recorded log
// of robot 0's bus and its team bus. The page must draw the map's shapes, both trajectories, the
// key pose, instances, the loop closure and the team link, show the car red and the trunk green
// where they project, then draw a pole the test appends to the log after the page loaded, and
// obey its replay controls (pause, a seek back to the start, live). It runs in a private network
// namespace with only loopback (root), so the page works offline, and it must ask for nothing but
// the viewer's own host (no CDN). No browser, Xvfb, node or puppeteer-core is a failure naming
// what to install, never a skip.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../deputy/netns.h"
#include "viewer_log_fixture.h"
#include "viewer_process.h"

using namespace slide;
using namespace slide::viewer_test;
namespace fs = std::filesystem;

namespace {

// Runs browser_check.mjs in `browser` (chromium | firefox) against a viewer replaying a log the
// test writes, and appends the pole once the check saw the recorded scene.
void checkPageIn(const std::string& browser) {
  ASSERT_EQ(test::enterPrivateNetns(), "") << "the browser tests run offline in a network namespace (as root)";
  const std::string web = std::string(SLIDE_SOURCE_DIR) + "/daemons/viewer/web";
  ASSERT_TRUE(fs::exists(web + "/node_modules/puppeteer-core"))
      << web << "/node_modules/puppeteer-core missing: run ./slide setup (npm ci there)";
  const fs::path dir = fs::path(SLIDE_BINARY_DIR) / "tests/viewer" / ("browser_" + browser);
  fs::remove_all(dir);
  fs::create_directories(dir / "logs");
  const std::int64_t t0 = 1700000000000000LL;
  {
    LogWriter w((dir / "logs/robot0.lcmlog").string());
    writeRobotRun(w, t0);
    LogWriter team((dir / "logs/team0.lcmlog").string());
    for (int i = 0; i < 5; ++i) team.write("TEAM_HEARTBEAT", heartbeatMsg(1, i), t0 + i * 100000);
  }
  const int port = freePort();
  ViewerProcess viewer({"--replay", dir.string(), "--follow", "--port", std::to_string(port), "--period", "0.2"},
                       (dir / "viewer.log").string(), port);
  ASSERT_TRUE(viewer.alive()) << "slide-viewer did not start: " << (dir / "viewer.log");

  const std::string cmd = "node " + std::string(SLIDE_SOURCE_DIR) + "/tests/viewer/browser_check.mjs " + browser + " " +
                          viewer.url() + " " + dir.string() + " > " + (dir / "browser.log").string() + " 2>&1";
  // The check runs in the background; once it saw the recorded scene it writes `phase1` and
  // waits for the pole appended here.
  std::thread check([&] {
    const int rc = std::system((cmd + "; echo $? > " + (dir / "browser.rc").string()).c_str());
    (void)rc;
  });
  bool phase1 = false;
  for (int i = 0; i < 1200 && !phase1 && !fs::exists(dir / "browser.rc"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    phase1 = fs::exists(dir / "phase1");
  }
  if (phase1) {
    LogWriter w((dir / "logs/robot0.lcmlog").string(), "ab");
    Cylinder pole;
    pole.root = {15, 8, 0};
    pole.radius = 0.15;
    pole.length = 5;
    w.write("OBJECT_MAP", mapMsg(0, {car(1, 10, 5), trunk(2, 20, -5), bush(3, 30, 5), {4, 80, pole, 0.9, 3}}),
            t0 + 2000000);
  }
  check.join();
  std::ifstream log(dir / "browser.log");
  std::stringstream out;
  out << log.rdbuf();
  std::ifstream rc_file(dir / "browser.rc");
  int rc = -1;
  rc_file >> rc;
  EXPECT_TRUE(phase1) << "the page never showed the recorded scene:\n" << out.str();
  EXPECT_EQ(rc, 0) << out.str();
  EXPECT_NE(out.str().find("update after load: drawn"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("replay controls: pause, seek to start, live"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("offline: every request went to"), std::string::npos) << out.str();
  EXPECT_TRUE(fs::exists(dir / "viewer.png"));
  EXPECT_TRUE(viewer.alive());
  EXPECT_EQ(viewer.stop(), 0);
}

}  // namespace

TEST(ViewerBrowser, PageDrawsTheSceneAndALaterMessage) { checkPageIn("chromium"); }

TEST(ViewerBrowser, PageDrawsTheSceneAndALaterMessageInFirefox) { checkPageIn("firefox"); }
