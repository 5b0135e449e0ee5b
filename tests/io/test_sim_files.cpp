// Readers for the simulator's files (ground-truth objects CSV, calib, TUM RGB-D, robot
// dataset folders): round trips and errors that name the file and the problem.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/calib_file.h"
#include "io/ground_truth_objects.h"
#include "io/io_error.h"
#include "io/kitti_scan.h"
#include "io/rgbd_files.h"
#include "io/robot_dataset.h"
#include "io/tum_trajectory.h"

using namespace slide;
namespace fs = std::filesystem;

namespace {
fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("slide_test_io_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

void writeText(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// Expects `f` to throw an IoError whose message contains every fragment.
template <class F>
void expectIoError(F f, std::initializer_list<std::string> fragments) {
  try {
    f();
    FAIL() << "no IoError thrown";
  } catch (const io::IoError& e) {
    for (const std::string& s : fragments) EXPECT_NE(std::string(e.what()).find(s), std::string::npos) << e.what();
  }
}

const char* kHeader = "id,class_id,shape,x,y,z,yaw,length,width,height,radius,axis_x,axis_y,axis_z,semantic,vx,vy\n";
}  // namespace

TEST(GroundTruthObjects, RoundTripAllShapes) {
  const fs::path dir = scratch("gt");
  std::vector<io::GroundTruthObject> in(3);
  in[0].object.class_id = 10;
  in[0].semantic = 10;
  in[0].object.model = Cuboid{poseFromXyzYaw(1, 2, 0.8, 0.4), {4.5, 1.8, 1.6}};
  in[0].velocity = {2, -1};
  in[1].object.class_id = 71;
  in[1].semantic = 71;
  in[1].object.model = Cylinder{{5, 6, -0.3}, Eigen::Vector3d(0.1, 0, 1).normalized(), 0.2, 12};
  in[2].object.class_id = 1;
  in[2].semantic = 100;
  in[2].object.model = Ellipsoid{{0, 1, 0.45}, 0.3, 0.9};
  for (int i = 0; i < 3; ++i) in[i].object.id = i + 1;
  io::writeGroundTruthObjects((dir / "objects.csv").string(), in);
  const auto out = io::readGroundTruthObjects((dir / "objects.csv").string());
  ASSERT_EQ(out.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(out[i].object.id, i + 1);
    EXPECT_EQ(out[i].object.shape(), in[i].object.shape());
    EXPECT_EQ(out[i].semantic, in[i].semantic);
    EXPECT_TRUE(out[i].object.position().isApprox(in[i].object.position(), 1e-5));
    EXPECT_TRUE(out[i].object.extent().isApprox(in[i].object.extent(), 1e-5));
  }
  EXPECT_NEAR(yawOf(std::get<Cuboid>(out[0].object.model).pose.linear()), 0.4, 1e-6);
  EXPECT_TRUE(std::get<Cylinder>(out[1].object.model).root.isApprox(Eigen::Vector3d(5, 6, -0.3), 1e-5));
  // A moving car moves.
  EXPECT_TRUE(out[0].at(2.0).position().isApprox(Eigen::Vector3d(5, 0, 0.8), 1e-5));
  fs::remove_all(dir);
}

TEST(GroundTruthObjects, ErrorsNameFileAndLine) {
  const fs::path dir = scratch("gterr");
  const std::string f = (dir / "objects.csv").string();
  expectIoError([&] { io::readGroundTruthObjects(f); }, {f, "cannot open"});
  writeText(f, "x,y\n");
  expectIoError([&] { io::readGroundTruthObjects(f); }, {f, "header"});
  writeText(f, std::string(kHeader) + "1,10,cuboid,1,2,3,0,4,2,1.5,0,0,0,1,10,0\n");
  expectIoError([&] { io::readGroundTruthObjects(f); }, {f, "line 2", "missing field vy"});
  writeText(f, std::string(kHeader) + "1,10,cuboid,1,2,abc,0,4,2,1.5,0,0,0,1,10,0,0\n");
  expectIoError([&] { io::readGroundTruthObjects(f); }, {f, "line 2", "field z", "abc"});
  writeText(f, std::string(kHeader) + "1,10,sphere,1,2,3,0,4,2,1.5,0,0,0,1,10,0,0\n");
  expectIoError([&] { io::readGroundTruthObjects(f); }, {f, "line 2", "shape: 'sphere'"});
  writeText(f, "id,class_id,shape,x,y,z\n1,10,cuboid,1,2,3\n");
  expectIoError([&] { io::readGroundTruthObjects(f); }, {f, "lacks column semantic"});
  fs::remove_all(dir);
}

TEST(CalibFile, RoundTripAndErrors) {
  const fs::path dir = scratch("calib");
  const std::string f = (dir / "calib.txt").string();
  const Pose T = poseFromXyzYaw(1, 2, 3, 0.3);
  io::writeCalibFile(f, {{"Tr", io::poseToCalib(T)}});
  EXPECT_TRUE(io::calibPose(io::readCalibFile(f), f, "Tr").isApprox(T, 1e-9));
  expectIoError([&] { io::calibPose(io::readCalibFile(f), f, "P0"); }, {f, "missing entry 'P0'"});
  writeText(f, "Tr: 1 0 0\n");
  expectIoError([&] { io::calibPose(io::readCalibFile(f), f, "Tr"); }, {f, "expected 12 values, got 3"});
  writeText(f, "Tr: 1 zero 0\n");
  expectIoError([&] { io::readCalibFile(f); }, {f, "line 1", "'zero'"});
  fs::remove_all(dir);
}

TEST(RobotDataset, LidarFolderChecks) {
  const fs::path dir = scratch("lidar");
  expectIoError([&] { io::openRobotDataset((dir / "none").string()); }, {"none", "missing dataset folder"});
  expectIoError([&] { io::openRobotDataset(dir.string()); }, {dir.string(), "neither a KITTI layout"});
  fs::create_directories(dir / "velodyne");
  fs::create_directories(dir / "labels");
  io::LabelledScan scan;
  scan.xyz = {{1, 2, 3}, {4, 5, 6}};
  scan.intensity = {0.1f, 0.2f};
  scan.semantic = {71, 40};
  scan.instance = {1, 0};
  for (const char* n : {"000000", "000001"}) {
    io::writeVelodyneBin((dir / "velodyne" / (std::string(n) + ".bin")).string(), scan);
    io::writeLabels((dir / "labels" / (std::string(n) + ".label")).string(), scan);
  }
  writeText(dir / "times.txt", "0.0\n0.1\n");
  writeText(dir / "odom.txt", "0.0 0 0 0 0 0 0 1\n0.1 1 0 0 0 0 0 1\n");
  const io::RobotDataset d = io::openRobotDataset(dir.string());
  EXPECT_EQ(d.size(), 2u);
  EXPECT_EQ(d.odometry.size(), 2u);
  EXPECT_EQ(d.scan(1).instance[0], 1);
  // Count mismatches and unparsable lines name the file.
  writeText(dir / "times.txt", "0.0\n");
  expectIoError([&] { io::openRobotDataset(dir.string()); }, {"times.txt", "1 entries for 2 frames"});
  writeText(dir / "times.txt", "0.0\n0.1\n");
  writeText(dir / "odom.txt", "0.0 0 0 0 0 0 0 1\nnot a pose\n");
  expectIoError([&] { io::openRobotDataset(dir.string()); }, {"odom.txt", "line 2"});
  writeText(dir / "odom.txt", "0.0 0 0 0 0 0 0 1\n0.1 1 0 0 0 0 0 1\n");
  // A truncated scan and a label file for the wrong number of points.
  { std::ofstream(dir / "velodyne" / "000001.bin", std::ios::binary | std::ios::app) << "xyz"; }
  expectIoError([&] { d.scan(1); }, {"000001.bin", "truncated"});
  io::LabelledScan one = scan;
  one.xyz.resize(1), one.intensity.resize(1);
  io::writeVelodyneBin((dir / "velodyne" / "000001.bin").string(), one);
  expectIoError([&] { d.scan(1); }, {"000001.label", "does not match"});
  fs::remove_all(dir);
}

TEST(RobotDataset, OdometryAtItsOwnRateIsInterpolatedAtFrameTimesAndMissesAreDropped) {
  const fs::path dir = scratch("async");
  fs::create_directories(dir / "velodyne");
  io::LabelledScan scan;
  scan.xyz = {{1, 2, 3}};
  scan.intensity = {0.5f};
  std::string times;
  for (int i = 0; i <= 10; ++i) {  // frames at 0.0, 0.1, ..., 1.0 s
    io::writeVelodyneBin((dir / "velodyne" / (std::to_string(100 + i) + ".bin")).string(), scan);
    times += std::to_string(0.1 * i) + "\n";
  }
  writeText(dir / "times.txt", times);
  expectIoError([&] { io::openRobotDataset(dir.string()); }, {"odom.txt", "missing"});
  // Analytic motion: x = 2 t, z = 0.1 t, yaw = 0.5 t (constant rates, so slerp is exact).
  auto truth = [](double t) { return poseFromXyzYaw(2 * t, 0, 0.1 * t, 0.5 * t); };
  std::vector<StampedPose> odom;
  for (int k = 3; k <= 97; ++k) {  // 100 Hz from 0.03 to 0.97 s, with a gap (0.41, 0.69)
    const double t = 0.01 * k;
    if (t > 0.415 && t < 0.685) continue;
    odom.push_back({t + 0.002, truth(t + 0.002)});  // odometry clock offset from the frames'
  }
  io::writeTum((dir / "odom.txt").string(), odom);
  io::DatasetOptions opt;
  opt.max_odometry_gap_s = 0.2;
  const io::RobotDataset d = io::openRobotDataset(dir.string(), opt);
  // 0.0 and 1.0 lie outside the odometry's span, 0.5 and 0.6 inside its 0.28 s gap.
  EXPECT_EQ(d.dropped.outside_span, 2u);
  EXPECT_EQ(d.dropped.gap, 2u);
  ASSERT_EQ(d.size(), 7u);
  const std::vector<std::size_t> ids{1, 2, 3, 4, 7, 8, 9};
  EXPECT_EQ(d.frame_ids, ids);
  for (std::size_t i = 0; i < d.size(); ++i) {
    EXPECT_NEAR(d.times[i], 0.1 * ids[i], 1e-9);
    EXPECT_TRUE(d.odometry[i].pose.isApprox(truth(d.times[i]), 1e-9)) << "frame " << ids[i];
  }
  EXPECT_EQ(d.scan(0).size(), 1u);
  // A larger limit bridges the gap; nothing is extrapolated past the span.
  opt.max_odometry_gap_s = 0.5;
  const io::RobotDataset wide = io::openRobotDataset(dir.string(), opt);
  EXPECT_EQ(wide.dropped.gap, 0u);
  EXPECT_EQ(wide.dropped.outside_span, 2u);
  // Odometry entirely after the frames: nothing to replay, said so.
  writeText(dir / "odom.txt", "5.0 0 0 0 0 0 0 1\n6.0 0 0 0 0 0 0 1\n");
  expectIoError([&] { io::openRobotDataset(dir.string()); }, {"none of the 11 frames", "11 outside"});
  fs::remove_all(dir);
}

TEST(RobotDataset, RgbdFolderChecks) {
  const fs::path dir = scratch("rgbd");
  fs::create_directories(dir / "rgb");
  fs::create_directories(dir / "depth");
  fs::create_directories(dir / "instances");
  cv::Mat color(4, 6, CV_8UC3, cv::Scalar(1, 2, 3)), depth(4, 6, CV_16UC1, cv::Scalar(1500));
  io::writePng((dir / "rgb" / "000000.png").string(), color);
  io::writePng((dir / "depth" / "000000.png").string(), depth);
  io::writeAssociations((dir / "associations.txt").string(), {{0.0, "rgb/000000.png", 0.0, "depth/000000.png"}});
  io::CameraCalib c;
  c.width = 6, c.height = 4, c.fx = c.fy = 5, c.cx = 3, c.cy = 2;
  io::writeCameraCalib((dir / "calib.txt").string(), c);
  expectIoError([&] { io::openRobotDataset(dir.string()); }, {"odom.txt", "missing"});
  writeText(dir / "odom.txt", "0.0 0 0 0 0 0 0 1\n");
  const io::RobotDataset d = io::openRobotDataset(dir.string());
  EXPECT_EQ(d.sensor, io::RobotDataset::Sensor::Rgbd);
  EXPECT_EQ(d.camera.width, 6);
  EXPECT_EQ(io::readDepthPng((dir / "depth" / "000000.png").string()).at<uint16_t>(1, 1), 1500);
  // Colour is not depth.
  expectIoError([&] { io::readDepthPng((dir / "rgb" / "000000.png").string()); }, {"000000.png", "16-bit"});
  // An instance mask naming an instance its list does not hold.
  cv::Mat mask(4, 6, CV_16UC1, cv::Scalar(0));
  mask.at<uint16_t>(0, 0) = 2;
  io::writeInstanceMask((dir / "instances" / "000000.png").string(), {mask, {71}, {5}});
  expectIoError([&] { io::readInstanceMask((dir / "instances" / "000000.png").string()); }, {"mask holds instance 2"});
  // A listed file that is missing.
  io::writeAssociations((dir / "associations.txt").string(), {{0.0, "rgb/000001.png", 0.0, "depth/000000.png"}});
  expectIoError([&] { io::openRobotDataset(dir.string()); }, {"000001.png", "missing file"});
  fs::remove_all(dir);
}

TEST(RobotDataset, RealSemanticKittiFolderWithoutOdometryIsAnError) {
  // The shared SemanticKITTI pair has scans and labels but no times or odometry: the folder is
  // refused (naming what is missing) rather than replayed with guessed poses.
  const std::string dir = std::string(SLIDE_DATA_DIR) + "/semantickitti/sequences/08";
  if (!fs::exists(dir + "/velodyne/000720.bin")) GTEST_SKIP();
  expectIoError([&] { io::openRobotDataset(dir); }, {"times.txt", "missing"});
  const io::LabelledScan a = io::readLabelledScan(dir + "/velodyne/000720.bin");
  EXPECT_EQ(a.size(), 126661u);
  EXPECT_TRUE(a.hasLabels());
}
