// The backend benchmark's map-size figures: each robot's own map encoded for sharing, and
// the raw LiDAR frames it drove through.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "map_size.h"

using namespace slide;

TEST(MapSize, OwnMapEncodedAndFramesCounted) {
  const graph_scenario::GraphScenario s = graph_scenario::makeIndoorScenario();
  ASSERT_EQ(s.robots.size(), 1u);
  const std::vector<Pose>& truth = s.robots[0].truth;
  std::vector<Pose> lidar;  // a frame between every two key poses, and one before the first
  lidar.push_back(Pose::Identity() * Eigen::Translation3d(100, 100, 100));
  for (std::size_t k = 0; k < truth.size(); ++k) {
    lidar.push_back(truth[k]);
    if (k + 1 < truth.size()) lidar.push_back(Eigen::Translation3d(0, 0, 0.01) * truth[k]);
  }
  const backend::BackendConfig cfg = backend::loadBackendConfig(std::string(SLIDE_SOURCE_DIR) + "/config/backend.yaml");
  const std::vector<RobotMapSize> sizes = robotMapSizes(s, cfg, lidar, 1000.0);
  ASSERT_EQ(sizes.size(), 1u);
  EXPECT_EQ(sizes[0].frames, static_cast<long>(2 * truth.size() - 1));
  EXPECT_DOUBLE_EQ(sizes[0].raw_bytes, sizes[0].frames * 1000.0 * 16.0);
  EXPECT_GT(sizes[0].objects, 30);
  EXPECT_GT(sizes[0].map_bytes, static_cast<std::size_t>(sizes[0].objects) * 4);
  EXPECT_LT(sizes[0].map_bytes, static_cast<std::size_t>(sizes[0].objects) * 100);

  const std::vector<Pose> elsewhere{Pose::Identity() * Eigen::Translation3d(-50, 0, 0)};
  EXPECT_THROW(robotMapSizes(s, cfg, elsewhere, 1000.0), std::runtime_error);
}

TEST(MapSize, MeanPointsPerScanFromFileSizes) {
  const auto dir = std::filesystem::temp_directory_path() / "slide_test_map_size";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  EXPECT_THROW(meanPointsPerScan(dir.string()), std::runtime_error);
  std::ofstream(dir / "a.bin") << std::string(32, 'x');
  std::ofstream(dir / "b.bin") << std::string(64, 'x');
  std::ofstream(dir / "notes.txt") << "not a scan";
  EXPECT_DOUBLE_EQ(meanPointsPerScan(dir.string()), 3.0);
  std::filesystem::remove_all(dir);
}
