// ./slide convert from a ROS 1 bag: to an LCM log (the robot-bus messages the sensor driver
// would publish, read back through lcm::LogFile: one SCAN and one ODOM per frame the bag reader
// keeps, a SENSOR_STATUS that ends FINISHED) and to a KITTI-layout folder that reads back with
// the same frames, points and poses.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <map>

#include "io/robot_dataset.h"
#include "slide/lidar_scan_t.hpp"
#include "slide/odometry_t.hpp"
#include "slide/stream_status_t.hpp"

namespace fs = std::filesystem;
using namespace slide;

namespace {
class Convert : public ::testing::Test {
 protected:
  fs::path dir;
  std::string bag;
  void SetUp() override {
    dir = fs::temp_directory_path() / ("slide_convert_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    bag = (dir / "velodyne.bag").string();
    const std::string cmd = "/usr/bin/python3 " + std::string(SLIDE_SOURCE_DIR) + "/tests/io/make_bags.py " + dir.string() +
                            " --only velodyne && /usr/bin/python3 " + SLIDE_SOURCE_DIR + "/tests/io/make_bags.py " +
                            dir.string() + " --only rgbd";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  void TearDown() override { fs::remove_all(dir); }
  // ./slide convert IN OUT ARGS with the built binaries; its exit status.
  static int convert(const std::string& in, const std::string& out, const std::string& args) {
    const std::string cmd = "SLIDE_NO_BUILD=1 SLIDE_BUILD=" + std::string(SLIDE_BINARY_DIR) + " " + SLIDE_SOURCE_DIR +
                            "/slide convert " + in + " " + out + " " + args + " >/dev/null 2>&1";
    return std::system(cmd.c_str());
  }
};
}  // namespace

TEST_F(Convert, BagToLcmLogReadsBackFrameByFrame) {
  const std::string log = (dir / "out.lcmlog").string();
  ASSERT_EQ(convert(bag, log, "--cloud-topic /velodyne_points --max-odom-gap 0.2"), 0);

  io::DatasetOptions o;
  o.bag.cloud_topic = "/velodyne_points";
  o.max_odometry_gap_s = 0.2;
  const io::RobotDataset d = io::openRobotDataset(bag, o);
  ASSERT_EQ(d.size(), 5u);  // 10 sweeps, 5 without odometry (tests/io/test_ros_bag.cpp)

  lcm::LogFile in(log, "r");
  ASSERT_TRUE(in.good()) << log;
  std::map<std::string, int> count;
  int8_t last_state = -1;
  std::size_t scans = 0, odoms = 0;
  while (const lcm::LogEvent* ev = in.readNextEvent()) {
    ++count[ev->channel];
    if (ev->channel == "SCAN") {
      lidar_scan_t m;
      ASSERT_GT(m.decode(ev->data, 0, ev->datalen), 0);
      ASSERT_LT(scans, d.size());
      EXPECT_EQ(m.num_points, static_cast<int>(d.scan(scans).size()));
      EXPECT_EQ(m.header.utime, std::llround(d.times[scans] * 1e6));
      ++scans;
    } else if (ev->channel == "ODOM") {
      odometry_t m;
      ASSERT_GT(m.decode(ev->data, 0, ev->datalen), 0);
      ASSERT_LT(odoms, d.size());
      EXPECT_NEAR(m.pose.position[0], d.odometry[odoms].pose.translation().x(), 1e-9);
      ++odoms;
    } else if (ev->channel == "SENSOR_STATUS") {
      stream_status_t m;
      ASSERT_GT(m.decode(ev->data, 0, ev->datalen), 0);
      last_state = m.state;
    }
  }
  EXPECT_EQ(count["SCAN"], 5);
  EXPECT_EQ(count["ODOM"], 5);
  EXPECT_EQ(last_state, stream_status_t::FINISHED);
}

TEST_F(Convert, LidarBagToFolderReadsBackTheSameFramesPointsAndPoses) {
  const std::string folder = (dir / "robot0").string();
  ASSERT_EQ(convert(bag, folder, "--cloud-topic /velodyne_points --max-odom-gap 0.2 --deskew"), 0);
  io::DatasetOptions o;
  o.bag.cloud_topic = "/velodyne_points";
  o.bag.deskew = true;
  o.max_odometry_gap_s = 0.2;
  const io::RobotDataset from_bag = io::openRobotDataset(bag, o), back = io::openRobotDataset(folder);
  ASSERT_EQ(back.size(), 5u);
  ASSERT_EQ(back.size(), from_bag.size());
  for (std::size_t i = 0; i < back.size(); ++i) {
    EXPECT_NEAR(back.times[i], from_bag.times[i], 1e-6);
    EXPECT_TRUE(back.odometry[i].pose.isApprox(from_bag.odometry[i].pose, 1e-8)) << i;
    const io::LabelledScan a = from_bag.scan(i), b = back.scan(i);  // sensor offset applied, deskewed
    ASSERT_EQ(a.size(), b.size());
    EXPECT_TRUE(std::equal(a.xyz.begin(), a.xyz.end(), b.xyz.begin())) << i;
    EXPECT_EQ(a.intensity, b.intensity);
  }
  EXPECT_NE(convert(bag, folder, "--cloud-topic /velodyne_points --max-odom-gap 0.2"), 0);  // not over a folder with files
  const std::string rgbd_args = "--color-topic /camera/color/image_raw --depth-topic /camera/aligned_depth_to_color/image_raw "
                                "--camera-info-topic /camera/color/camera_info --odom-topic /odom";
  EXPECT_NE(convert((dir / "rgbd.bag").string(), (dir / "rgbd").string(), rgbd_args), 0);  // LiDAR only
  EXPECT_FALSE(fs::exists(dir / "rgbd" / "odom.txt"));
}
