// ROS 1 bags with real drivers' layouts (written by tests/io/make_bags.py through Debian's
// python3-rosbag): field decoding, odometry interpolation against the analytic motion, deskew
// against sweeps simulated with motion, RGBD encodings, and errors for bad bags.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <random>

#include "geometry/deskew.h"
#include "io/io_error.h"
#include "io/point_cloud2.h"
#include "io/robot_dataset.h"
#include "io/ros_bag.h"

namespace fs = std::filesystem;
using namespace slide;

namespace {
constexpr double kT0 = 1700000000.0;  // make_bags.py's start time
constexpr double kV = 2.0, kW = 0.5;

Pose truth(double t) { return poseFromXyzYaw(kV * (t - kT0), 0, 0, kW * (t - kT0)); }

class RosBag : public ::testing::Test {
 protected:
  static fs::path dir;
  static void SetUpTestSuite() {
    dir = fs::temp_directory_path() / ("slide_bags_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string cmd = "/usr/bin/python3 " + std::string(SLIDE_SOURCE_DIR) + "/tests/io/make_bags.py " + dir.string();
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  static void TearDownTestSuite() { fs::remove_all(dir); }
  static std::string bag(const char* name) { return (dir / name).string(); }
};
fs::path RosBag::dir;

// Largest distance of the scan's points, put in the odometry frame by the frame's pose, from
// make_bags.py's world: a vertical cylinder of radius 10 m about the odometry origin.
double worstCylinderError(const io::LabelledScan& s, const Pose& T_odom_body) {
  double worst = 0;
  for (const Eigen::Vector3f& p : s.xyz) {
    const Eigen::Vector3d w = T_odom_body * p.cast<double>();
    worst = std::max(worst, std::abs(std::hypot(w.x(), w.y()) - 10.0));
  }
  return worst;
}

template <class F>
void expectIoError(F f, std::initializer_list<std::string> fragments) {
  try {
    f();
    ADD_FAILURE() << "no IoError";
  } catch (const io::IoError& e) {
    for (const std::string& s : fragments) EXPECT_NE(std::string(e.what()).find(s), std::string::npos) << e.what();
  }
}

io::DatasetOptions ousterOptions(bool deskew) {
  io::DatasetOptions o;
  o.bag.cloud_topic = "/os_cloud_node/points";
  o.bag.odom_topic = "/odom";
  o.bag.deskew = deskew;
  return o;
}

// The topics of the RGBD test bags (a RealSense's color / aligned depth / camera info, /odom).
io::DatasetOptions realSenseOptions() {
  io::DatasetOptions o;
  o.bag.color_topic = "/camera/color/image_raw";
  o.bag.depth_topic = "/camera/aligned_depth_to_color/image_raw";
  o.bag.camera_info_topic = "/camera/color/camera_info";
  o.bag.odom_topic = "/odom";
  return o;
}
}  // namespace

TEST_F(RosBag, ListsTopicsTypesCountsAndRates) {
  const std::vector<io::BagTopicInfo> t = io::listBagTopics(bag("ouster.bag"));
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0].topic, "/odom");
  EXPECT_EQ(t[0].type, "nav_msgs/Odometry");
  EXPECT_NEAR(t[0].rateHz(), 100.0, 0.5);
  EXPECT_EQ(t[1].type, "sensor_msgs/PointCloud2");
  EXPECT_EQ(t[1].messages, 3u);
  EXPECT_NEAR(t[1].rateHz(), 10.0, 0.1);
}

TEST_F(RosBag, Os1OrganisedCloudDecodedByFieldsAndDeskewedFromPerPointTimes) {
  const io::RobotDataset raw = io::openRobotDataset(bag("ouster.bag"), ousterOptions(false));
  ASSERT_EQ(raw.size(), 3u);
  EXPECT_EQ(raw.dropped.total(), 0u);
  const io::LabelledScan s = raw.scan(1);
  EXPECT_EQ(s.size(), 64u * 1024u - 19u);  // 11 zero (no return) and 8 NaN points skipped
  const auto [lo, hi] = std::minmax_element(s.intensity.begin(), s.intensity.end());
  EXPECT_EQ(*lo, 100.f);  // intensity of beam r is 100 + r
  EXPECT_EQ(*hi, 163.f);
  EXPECT_NE(raw.reader->dropSummary().find("19 NaN/zero"), std::string::npos);
  // Odometry at 100 Hz interpolated at the frame stamps; /tf_static puts the sensor 0.5 m up.
  for (std::size_t i = 0; i < raw.size(); ++i) EXPECT_TRUE(raw.odometry[i].pose.isApprox(truth(raw.times[i]), 1e-6));
  // The robot moves 2 m/s and turns 0.5 rad/s during the 0.1 s sweep: points smear by
  // decimetres unless deskewed, and land on the world's cylinder to a few millimetres if so.
  const double smeared = worstCylinderError(s, raw.odometry[1].pose);
  const io::RobotDataset fixed = io::openRobotDataset(bag("ouster.bag"), ousterOptions(true));
  const double deskewed = worstCylinderError(fixed.scan(1), fixed.odometry[1].pose);
  EXPECT_GT(smeared, 0.1);
  EXPECT_LT(deskewed, 0.01);
  EXPECT_EQ(fixed.scan(1).size(), s.size());
}

TEST_F(RosBag, Vlp16WithTfChainOdometryAt10HzAndAGap) {
  io::DatasetOptions o;
  o.bag.cloud_topic = "/velodyne_points";
  o.bag.deskew = true;  // odometry from /tf odom -> base_link; sensor from /tf_static
  o.max_odometry_gap_s = 0.2;
  const io::RobotDataset d = io::openRobotDataset(bag("velodyne.bag"), o);
  // Stamps 0.15 .. 1.05 s; /tf covers 0 .. 1 s with nothing between 0.4 and 0.8 s.
  EXPECT_EQ(d.dropped.gap, 4u);
  EXPECT_EQ(d.dropped.outside_span, 1u);
  ASSERT_EQ(d.size(), 5u);
  for (std::size_t i = 0; i < d.size(); ++i) {
    EXPECT_TRUE(d.odometry[i].pose.isApprox(truth(d.times[i]), 1e-6)) << i;  // slerp/linear exact for constant rates
    EXPECT_LT(worstCylinderError(d.scan(i), d.odometry[i].pose), 0.01) << i;  // float32 time, relative to the sweep's end
  }
  EXPECT_EQ(d.scan(0).size(), 16u * 450u);
}

TEST_F(RosBag, LivoxAbsoluteNanosecondTimestamps) {
  io::DatasetOptions o;
  o.bag.cloud_topic = "/livox/lidar";
  o.bag.odom_topic = "/odom";
  o.bag.deskew = true;
  const io::RobotDataset d = io::openRobotDataset(bag("livox.bag"), o);
  ASSERT_EQ(d.size(), 3u);
  // The cloud is in base_link, no sensor offset: its points are 0.5 m low of the cylinder's
  // z but its radius is what is checked.
  EXPECT_LT(worstCylinderError(d.scan(2), d.odometry[2].pose), 0.01);
}

TEST_F(RosBag, RealSenseDepthAndColourPairs) {
  const io::DatasetOptions o = realSenseOptions();
  for (const char* name : {"rgbd.bag", "rgbd32.bag"}) {
    SCOPED_TRACE(name);
    const io::RobotDataset d = io::openRobotDataset(bag(name), o);
    ASSERT_EQ(d.sensor, io::RobotDataset::Sensor::Rgbd);
    ASSERT_EQ(d.size(), 5u);
    EXPECT_EQ(d.camera.width, 64);
    EXPECT_EQ(d.camera.fx, 50.0);
    EXPECT_EQ(d.camera.fy, 51.0);
    EXPECT_EQ(d.camera.cx, 32.0);
    EXPECT_EQ(d.camera.cy, 24.0);
    EXPECT_TRUE(d.warnings.empty()) << d.warnings.front();  // zero distortion: nothing to say
    const io::RgbdImages f = d.rgbd(2);
    ASSERT_EQ(f.color.type(), CV_8UC3);
    const cv::Vec3b px = f.color.at<cv::Vec3b>(10, 10);  // BGR in memory whatever the encoding
    if (std::string(name) == "rgbd.bag") EXPECT_EQ(px, cv::Vec3b(30, 22, 10));
    else EXPECT_EQ(px, cv::Vec3b(10, 22, 30));
    ASSERT_EQ(f.depth.type(), CV_16UC1);
    EXPECT_EQ(f.depth.at<uint16_t>(5, 0), 0);      // no depth (0 mm / NaN m)
    EXPECT_EQ(f.depth.at<uint16_t>(5, 20), 1200);  // 1.2 m in millimetres
    // The frame's pose is the camera's x-forward frame: body pose, 0.1 m ahead and 0.3 m up,
    // same orientation (the optical rotation from /tf_static undone).
    const Pose expect = truth(d.times[2]) * poseFromXyzYaw(0.1, 0, 0.3, 0);
    EXPECT_TRUE(d.odometry[2].pose.isApprox(expect, 1e-6));
  }
}

TEST_F(RosBag, ErrorsNameBagTopicAndProblem) {
  io::DatasetOptions o = ousterOptions(false);
  o.bag.cloud_topic = "/points";
  expectIoError([&] { io::openRobotDataset(bag("ouster.bag"), o); },
                {"ouster.bag", "'/points' is not in the bag", "/odom"});
  o.bag.cloud_topic = "/odom";
  expectIoError([&] { io::openRobotDataset(bag("ouster.bag"), o); },
                {"'/odom' has type nav_msgs/Odometry", "PointCloud2"});
  o = ousterOptions(false);
  o.bag.odom_topic.clear();
  expectIoError([&] { io::openRobotDataset(bag("ouster.bag"), o); }, {"no odometry", "'odom' to 'base_link'"});
  io::DatasetOptions v;
  v.bag.cloud_topic = "/velodyne_points";
  v.bag.body_frame = "somewhere";
  expectIoError([&] { io::openRobotDataset(bag("velodyne.bag"), v); }, {"no odometry"});
  expectIoError([&] { io::listBagTopics(bag("none.bag")); }, {"none.bag"});
}

TEST_F(RosBag, TruncatedAndCorruptedBagsGiveIoErrorsNeverACrash) {
  std::ifstream in(bag("velodyne.bag"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  io::DatasetOptions o;
  o.bag.cloud_topic = "/velodyne_points";
  o.max_odometry_gap_s = 0.2;
  const std::string cut = (dir / "cut.bag").string();
  auto readAll = [&](const std::string& path) {
    const io::RobotDataset d = io::openRobotDataset(path, o);
    for (std::size_t i = 0; i < d.size(); ++i) {
      try {
        d.scan(i);
      } catch (const io::IoError&) {  // a bad frame is the caller's to drop
      }
    }
  };
  for (std::size_t keep : {std::size_t(0), std::size_t(13), std::size_t(4096), bytes.size() / 2, bytes.size() - 100}) {
    std::ofstream(cut, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(keep));
    expectIoError([&] { readAll(cut); }, {"cut.bag"});
  }
  std::mt19937 rng(7);
  int opened = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::string bad = bytes;
    for (int k = 0; k < 8; ++k) bad[rng() % bad.size()] = static_cast<char>(rng());
    std::ofstream(cut, std::ios::binary).write(bad.data(), static_cast<std::streamsize>(bad.size()));
    try {
      readAll(cut);
      ++opened;
    } catch (const io::IoError& e) {
      EXPECT_NE(std::string(e.what()).find("cut.bag"), std::string::npos) << e.what();
    }
  }
  RecordProperty("corrupted_bags_opened", opened);
}

TEST_F(RosBag, CameraInfoDistortionIsReportedOnceNamingTheTopic) {
  const io::DatasetOptions o = realSenseOptions();
  const io::RobotDataset d = io::openRobotDataset(bag("rgbd_distorted.bag"), o);  // five CameraInfos, all distorted
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("'/camera/color/camera_info'"), std::string::npos) << d.warnings[0];
  EXPECT_NE(d.warnings[0].find("plumb_bob distortion, which is not corrected"), std::string::npos) << d.warnings[0];
  EXPECT_EQ(d.camera.cx, 32.0);
  EXPECT_EQ(d.rgbd(0).color.cols, 64);  // read as it is
}

TEST_F(RosBag, CompressedBz2AndLz4BagsReadLikeTheUncompressedOne) {
  io::DatasetOptions o;
  o.bag.cloud_topic = "/velodyne_points";
  o.max_odometry_gap_s = 0.2;
  const io::RobotDataset plain = io::openRobotDataset(bag("velodyne.bag"), o);
  for (const char* name : {"velodyne_bz2.bag", "velodyne_lz4.bag"}) {
    SCOPED_TRACE(name);
    EXPECT_EQ(io::listBagTopics(bag(name)).size(), 3u);
    const io::RobotDataset d = io::openRobotDataset(bag(name), o);
    ASSERT_EQ(d.size(), plain.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      EXPECT_EQ(d.times[i], plain.times[i]);
      EXPECT_TRUE(d.odometry[i].pose.isApprox(plain.odometry[i].pose, 1e-12));
      const io::LabelledScan a = plain.scan(i), b = d.scan(i);
      ASSERT_EQ(a.size(), b.size());
      EXPECT_TRUE(std::equal(a.xyz.begin(), a.xyz.end(), b.xyz.begin()));
      EXPECT_EQ(a.intensity, b.intensity);
    }
  }
}

TEST_F(RosBag, BodyFrameAboveOrBelowTheOdometryChildFollowsTheTfChainAtEachFrameTime) {
  // frames.bag: nav_msgs/Odometry of imu_link, 0.2 m above base_link (/tf_static); a joint
  // imu_link -> gimbal moving on /tf from 0 to 0.5 s (0.1 m ahead, yaw 0.3 rad/s).
  io::DatasetOptions o;
  o.bag.cloud_topic = "/points";
  o.bag.odom_topic = "/odom";
  o.bag.body_frame = "base_link";  // above the odometry's child: the static chain inverted
  const io::RobotDataset base = io::openRobotDataset(bag("frames.bag"), o);
  ASSERT_EQ(base.size(), 9u);
  for (std::size_t i = 0; i < base.size(); ++i) EXPECT_TRUE(base.odometry[i].pose.isApprox(truth(base.times[i]), 1e-6)) << i;
  o.bag.body_frame = "gimbal";  // below it through a moving joint: its pose at each frame's time
  o.bag.T_body_sensor = Pose::Identity();
  const io::RobotDataset g = io::openRobotDataset(bag("frames.bag"), o);
  EXPECT_EQ(g.dropped.outside_span, 4u);  // frames after the joint's last /tf sample have no pose
  ASSERT_EQ(g.size(), 5u);
  for (std::size_t i = 0; i < g.size(); ++i) {
    const double t = g.times[i] - kT0;
    const Pose expect = poseFromXyzYaw(kV * t, 0, 0.2, kW * t) * poseFromXyzYaw(0.1, 0, 0, 0.3 * t);
    EXPECT_TRUE(g.odometry[i].pose.isApprox(expect, 1e-6)) << i << "\n" << g.odometry[i].pose.matrix();
  }
  o.bag.body_frame = "somewhere";
  expectIoError([&] { io::openRobotDataset(bag("frames.bag"), o); },
                {"frames.bag", "topic '/odom'", "child frame 'imu_link'", "body frame 'somewhere'"});
}

TEST_F(RosBag, ErrorsNameTheMessageIndexTheEncodingAndAnUnindexedOrTruncatedBag) {
  io::DatasetOptions o;
  o.bag.cloud_topic = "/points";
  o.bag.odom_topic = "/odom";
  const io::RobotDataset d = io::openRobotDataset(bag("broken.bag"), o);
  ASSERT_EQ(d.size(), 4u);
  EXPECT_EQ(d.scan(0).size(), 100u);
  expectIoError([&] { d.scan(1); }, {"broken.bag", "topic '/points' message 1: message ends after"});
  expectIoError([&] { d.scan(2); }, {"broken.bag", "topic '/points' message 2: data holds 600 bytes, rows need 1200"});
  EXPECT_EQ(d.scan(3).size(), 100u);

  io::DatasetOptions c;
  c.bag.color_topic = "/camera/color/image_raw";
  c.bag.depth_topic = "/camera/aligned_depth_to_color/image_raw";
  c.bag.camera_info_topic = "/camera/color/camera_info";
  c.bag.odom_topic = "/odom";
  expectIoError([&] { io::openRobotDataset(bag("rgbd_yuv.bag"), c); },  // refused when opened, not frame by frame
                {"rgbd_yuv.bag", "topic '/camera/color/image_raw' message 0: unsupported colour encoding 'yuv422' (bgr8, rgb8)"});

  // A recording that was cut: its header's index position is still 0 ...
  std::ifstream in(bag("velodyne.bag"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = bytes.find("index_pos=");
  ASSERT_NE(at, std::string::npos);
  std::string unindexed = bytes;
  std::fill_n(unindexed.begin() + static_cast<std::ptrdiff_t>(at + 10), 8, '\0');
  const std::string cut = (dir / "unindexed.bag").string();
  std::ofstream(cut, std::ios::binary).write(unindexed.data(), static_cast<std::streamsize>(unindexed.size()));
  expectIoError([&] { io::listBagTopics(cut); }, {"unindexed.bag", "bag is not indexed", "rosbag reindex"});
  // ... or it points past the end of a file that lost its tail.
  const std::string half = (dir / "half.bag").string();
  std::ofstream(half, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
  expectIoError([&] { io::openRobotDataset(half, o); }, {"half.bag", "truncated"});
}

TEST(PointCloud2, FieldsThatDoNotFitAreRefusedByName) {
  io::CloudLayout l;
  l.height = 1, l.width = 2, l.point_step = 12, l.row_step = 24;
  l.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}};
  std::vector<uint8_t> data(24, 0);
  const float p[6] = {1, 2, 3, NAN, 0, 0};
  std::memcpy(data.data(), p, 24);
  const io::DecodedCloud c = io::decodeCloud(l, data.data(), data.size(), 0);
  EXPECT_EQ(c.xyz.size(), 1u);
  EXPECT_EQ(c.skipped, 1u);
  EXPECT_TRUE(c.time.empty());
  EXPECT_THROW(io::decodeCloud(l, data.data(), 20, 0), std::invalid_argument);  // rows past the data
  l.fields.push_back({"intensity", 10, 7, 1});                                // past point_step
  try {
    io::decodeCloud(l, data.data(), data.size(), 0);
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'intensity'"), std::string::npos);
  }
  l.fields.pop_back();
  l.fields.erase(l.fields.begin());
  EXPECT_THROW(io::decodeCloud(l, data.data(), data.size(), 0), std::invalid_argument);  // no x
}
