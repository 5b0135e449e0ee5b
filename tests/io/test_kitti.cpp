#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/io_error.h"
#include "io/kitti_poses.h"
#include "io/kitti_scan.h"

using namespace slide;

namespace {
const std::string kData = SLIDE_DATA_DIR;
bool haveData() { return std::filesystem::exists(kData + "/semantickitti/sequences/08/velodyne/000720.bin"); }
}  // namespace

TEST(KittiScan, RealSemanticKittiScans) {
  if (!haveData()) GTEST_SKIP() << "real data not found at " << kData;
  const std::string dir = kData + "/semantickitti/sequences/08/velodyne/";
  const io::LabelledScan a = io::readLabelledScan(dir + "000720.bin");
  const io::LabelledScan b = io::readLabelledScan(dir + "001500.bin");
  EXPECT_EQ(a.size(), 126661u);
  EXPECT_EQ(b.size(), 126458u);
  ASSERT_TRUE(a.hasLabels());
  std::size_t cars = 0, with_instance = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    cars += a.semantic[i] == 10;
    with_instance += a.semantic[i] == 10 && a.instance[i] != 0;
  }
  EXPECT_GT(cars, 1000u);
  EXPECT_EQ(with_instance, cars);  // every car point belongs to an instance
}

TEST(KittiScan, WriteReadRoundTripAndErrors) {
  io::LabelledScan s;
  s.xyz = {{1, 2, 3}, {-4, 5.5f, 6}};
  s.intensity = {0.25f, 0.5f};
  s.semantic = {10, 71};
  s.instance = {3, 0};
  const std::string dir = testing::TempDir() + "kitti_rt/";
  std::filesystem::create_directories(dir + "velodyne");
  std::filesystem::create_directories(dir + "labels");
  io::writeVelodyneBin(dir + "velodyne/000000.bin", s);
  io::writeLabels(dir + "labels/000000.label", s);
  const io::LabelledScan r = io::readLabelledScan(dir + "velodyne/000000.bin");
  EXPECT_EQ(r.xyz, s.xyz);
  EXPECT_EQ(r.semantic, s.semantic);
  EXPECT_EQ(r.instance, s.instance);

  std::ofstream(dir + "bad.bin", std::ios::binary) << "0123456789";
  try {
    io::readVelodyneBin(dir + "bad.bin");
    FAIL();
  } catch (const io::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.bin: truncated"), std::string::npos);
  }
  io::LabelledScan three = s;
  three.xyz.push_back({0, 0, 0});
  EXPECT_THROW(io::readLabels(dir + "labels/000000.label", three), io::IoError);
  EXPECT_THROW(io::readVelodyneBin(dir + "missing.bin"), io::IoError);
}

TEST(KittiPoses, RealSequence07) {
  if (!haveData()) GTEST_SKIP();
  const auto cam = io::readKittiPoses(kData + "/kitti/poses/07.txt");
  EXPECT_EQ(cam.size(), 1101u);
  EXPECT_EQ(io::readKittiTimes(kData + "/kitti/poses/times_07.txt").size(), cam.size());
  const auto lidar = io::kittiLidarPoses(cam, io::kittiVeloToCamTr0410());
  EXPECT_LT((lidar[0].matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-6);
  // 50 m driven by frame 100 (first forward along LiDAR x), staying near the ground plane.
  EXPECT_GT(lidar[100].translation().norm(), 40.0);
  EXPECT_GT(lidar[50].translation().x(), 4.0);
  EXPECT_LT(std::abs(lidar[100].translation().z()), 1.0);
}

TEST(KittiPoses, WriteReadAndErrors) {
  const std::string path = testing::TempDir() + "poses.txt";
  const std::vector<Pose> poses = {Pose::Identity(), poseFromXyzYaw(1, 2, 3, 0.4)};
  io::writeKittiPoses(path, poses);
  const auto back = io::readKittiPoses(path);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_TRUE(back[1].isApprox(poses[1], 1e-8));
  std::ofstream(path) << "1 0 0 0 0 1 0 0 0 0 1\n";
  try {
    io::readKittiPoses(path);
    FAIL();
  } catch (const io::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("line 1: expected 12"), std::string::npos);
  }
}
