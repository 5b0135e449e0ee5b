// ./slide convert BAG OUT.lcmlog writes the robot-bus messages the sensor driver would publish:
// the log reads back through lcm::LogFile with one SCAN and one ODOM per frame the bag reader
// keeps, the same points and poses, and a SENSOR_STATUS that ends FINISHED.
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

TEST(Convert, BagToLcmLogReadsBackFrameByFrame) {
  const fs::path dir = fs::temp_directory_path() / ("slide_convert_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string src = SLIDE_SOURCE_DIR, bag = (dir / "velodyne.bag").string(), log = (dir / "out.lcmlog").string();
  ASSERT_EQ(std::system(("/usr/bin/python3 " + src + "/tests/io/make_bags.py " + dir.string() + " --only velodyne").c_str()), 0);
  const std::string cmd = "SLIDE_NO_BUILD=1 SLIDE_BUILD=" + std::string(SLIDE_BINARY_DIR) + " " + src + "/slide convert " + bag +
                          " " + log + " --cloud-topic /velodyne_points --max-odom-gap 0.2 >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;

  DatasetOptions o;
  o.bag.cloud_topic = "/velodyne_points";
  o.max_odometry_gap_s = 0.2;
  const RobotDataset d = openRobotDataset(bag, o);
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
  fs::remove_all(dir);
}
