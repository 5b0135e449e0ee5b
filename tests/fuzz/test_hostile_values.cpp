// Absurd values must not hang or kill a stage (issue 16 finding 3): far objects in the
// back-end's association grid and optimizer, loop bounds in the configuration. Each test runs
// under an alarm: a hang kills the test binary instead of the suite waiting for it.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <thread>

#include "backend/landmark_grid.h"
#include "backend/optimizer.h"
#include "frontend/frontend_config.h"
#include "graph_scenario/scenario.h"

#include "watchdog.h"

using namespace slide;
namespace fs = std::filesystem;

using slide::test::secondsSince;
using slide::test::Watchdog;

TEST(HostileValues, LandmarkGridLookUpOfAFarObjectScansOnlyTheOccupiedCells) {
  Watchdog dog(20);
  backend::LandmarkGrid grid(4.0);
  for (int i = 0; i < 100; ++i) grid.move(i, Eigen::Vector3d(i * 3.0, 0, 0));
  grid.move(100, Eigen::Vector3d(2e9, 0, 0));
  // Before: a radius of 5e6 m (a far object's range-proportional slack) meant 6e12 cells.
  for (double r : {1e6, 5e6, 2e9, 1e300}) {
    std::vector<int> out;
    grid.near(Eigen::Vector3d(10, 0, 0), r, out);
    EXPECT_EQ(out.size(), r >= 2e9 ? 101u : 100u) << "radius " << r;
  }
  std::vector<int> out;
  grid.near(Eigen::Vector3d(2e9, 0, 0), 5.0, out);
  EXPECT_EQ(out, std::vector<int>{100});
  out.clear();
  grid.near(Eigen::Vector3d(std::nan(""), 0, 0), 5.0, out);
  EXPECT_TRUE(out.empty());
  out.clear();
  grid.near(Eigen::Vector3d(12, 0, 0), 1.0, out);  // the plain small look-up is unchanged
  EXPECT_EQ(out, std::vector<int>({3, 4, 5}));  // cells 2 and 3
}

TEST(HostileValues, OptimizerDropsObjectsBeyondTheSensorRangeAndStaysQuick) {
  Watchdog dog(60);
  const graph_scenario::GraphScenario s = graph_scenario::makeIndoorScenario(1);
  backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(opt.addBundle(s.robots[0].bundles[i]).accepted);
  for (double far : {1e6, 1e7, 2e9}) {
    KeyPoseBundle b = s.robots[0].bundles[opt.numKeyPoses()];
    ASSERT_FALSE(b.objects.empty());
    b.objects[0] = transformObject(Pose(Eigen::Translation3d(far, 0, 0)), b.objects[0]);
    const auto t0 = std::chrono::steady_clock::now();
    const backend::UpdateResult r = opt.addBundle(b);
    EXPECT_TRUE(r.accepted) << r.reason;
    EXPECT_LT(secondsSince(t0), 5.0) << "object at " << far << " m";
    bool warned = false;
    for (const auto& w : r.warnings) warned |= w.find("out of range") != std::string::npos;
    EXPECT_TRUE(warned) << "no warning for an object " << far << " m away";
  }
}

TEST(HostileValues, FrontendConfigRefusesLoopBoundsOutsideTheirRange) {
  const fs::path dir = fs::temp_directory_path() / ("slide_hostile_cfg_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string src = std::string(SLIDE_SOURCE_DIR) + "/config/frontend.yaml";
  std::ifstream in(src);
  std::stringstream text;
  text << in.rdbuf();
  for (const auto& [key, bad] : std::vector<std::pair<std::string, std::string>>{
           {"ransac_iterations: 60", "ransac_iterations: 2000000000"}}) {
    std::string t = text.str();
    const auto at = t.find(key);
    ASSERT_NE(at, std::string::npos) << key << " not in " << src;
    t.replace(at, key.size(), bad);
    std::ofstream((dir / "f.yaml").string()) << t;
    try {
      frontend::loadFrontendConfig((dir / "f.yaml").string());
      ADD_FAILURE() << bad << " was accepted";
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find("ransac_iterations"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("at most"), std::string::npos) << e.what();
    }
  }
  fs::remove_all(dir);
}

