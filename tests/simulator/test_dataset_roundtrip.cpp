// Simulator output reads back through the project's readers.
#include <gtest/gtest.h>

#include <filesystem>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "io/ground_truth_objects.h"
#include "io/kitti_scan.h"
#include "io/robot_dataset.h"
#include "simulator/dataset_writer.h"

using namespace slide;
namespace fs = std::filesystem;

namespace {
fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("slide_test_sim_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  return p;
}
}  // namespace

TEST(Dataset, LidarScenarioReadsBack) {
  simulator::ScenarioSpec spec;
  spec.world = "urban";
  spec.robots = 2;
  spec.frames = 4;
  const simulator::Scenario sc = simulator::buildScenario(spec);
  const fs::path out = scratch("lidar");
  simulator::SensorOptions sensors;
  sensors.lidar = simulator::lidarModel("vlp-16");
  const simulator::GenerationStats st = simulator::writeScenarioDataset(sc, sensors, out.string());
  EXPECT_EQ(st.frames, 8u);

  const std::vector<io::GroundTruthObject> objects = io::readGroundTruthObjects((out / "objects.csv").string());
  ASSERT_EQ(objects.size(), sc.world.objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i) {
    EXPECT_EQ(objects[i].object.id, static_cast<int64_t>(i + 1));
    EXPECT_EQ(objects[i].object.class_id, sc.world.objects[i].object.class_id);
    EXPECT_TRUE(objects[i].object.position().isApprox(sc.world.objects[i].object.position(), 1e-5));
    EXPECT_TRUE(objects[i].object.extent().isApprox(sc.world.objects[i].object.extent(), 1e-5));
    EXPECT_TRUE(objects[i].velocity.isApprox(sc.world.objects[i].velocity, 1e-5));
  }
  for (int r = 0; r < 2; ++r) {
    const io::RobotDataset d = io::openRobotDataset((out / ("robot" + std::to_string(r))).string());
    EXPECT_EQ(d.sensor, io::RobotDataset::Sensor::Lidar);
    ASSERT_EQ(d.size(), 4u);
    ASSERT_EQ(d.odometry.size(), 4u);
    ASSERT_EQ(d.ground_truth.size(), 4u);
    EXPECT_TRUE(d.ground_truth[3].pose.isApprox(sc.robots[r].ground_truth.poses[3], 1e-6));
    EXPECT_TRUE(d.odometry[3].pose.isApprox(sc.robots[r].odometry[3], 1e-6));
    const io::LabelledScan scan = d.scan(2);
    ASSERT_TRUE(scan.hasLabels());
    EXPECT_GT(scan.size(), 5000u);
    // Every instance id names an object of the CSV whose class matches the point label.
    for (std::size_t i = 0; i < scan.size(); ++i)
      if (scan.instance[i] != 0) {
        ASSERT_LE(scan.instance[i], objects.size());
        ASSERT_EQ(scan.semantic[i], objects[scan.instance[i] - 1].semantic);
      }
  }
  fs::remove_all(out);
}

TEST(Dataset, OutputDoesNotDependOnThreads) {
  simulator::ScenarioSpec spec;
  spec.world = "urban";  // moving cars: frames depend on time
  spec.robots = 2;
  spec.frames = 3;
  const simulator::Scenario sc = simulator::buildScenario(spec);
  simulator::SensorOptions sensors;
  sensors.lidar = simulator::lidarModel("vlp-16");
  const fs::path a = scratch("threads1"), b = scratch("threads2");
  simulator::writeScenarioDataset(sc, sensors, a.string(), {}, 1);
  simulator::writeScenarioDataset(sc, sensors, b.string(), {}, 2);
  for (const char* f : {"robot1/velodyne/000002.bin", "robot1/labels/000002.label", "robot0/odom.txt", "objects.csv"}) {
    std::ifstream fa(a / f, std::ios::binary), fb(b / f, std::ios::binary);
    const std::string sa((std::istreambuf_iterator<char>(fa)), {}), sb((std::istreambuf_iterator<char>(fb)), {});
    EXPECT_FALSE(sa.empty()) << f;
    EXPECT_EQ(sa, sb) << f;
  }
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(Dataset, RgbdScenarioReadsBack) {
  simulator::ScenarioSpec spec;
  spec.world = "indoor";
  spec.robots = 1;
  spec.frames = 2;
  const simulator::Scenario sc = simulator::buildScenario(spec);
  const fs::path out = scratch("rgbd");
  simulator::SensorOptions sensors;
  sensors.sensor = "rgbd";
  simulator::writeScenarioDataset(sc, sensors, out.string());
  const io::RobotDataset d = io::openRobotDataset((out / "robot0").string());
  EXPECT_EQ(d.sensor, io::RobotDataset::Sensor::Rgbd);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d.camera.width, 640);
  EXPECT_NEAR(d.camera.depth_scale, 0.001, 1e-12);
  const io::RgbdImages f = d.rgbd(1);
  const cv::Mat &depth = f.depth, &color = f.color;
  ASSERT_TRUE(f.mask.has_value());
  EXPECT_EQ(depth.rows, 480);
  EXPECT_EQ(color.type(), CV_8UC3);
  EXPECT_GT(cv::countNonZero(depth), 640 * 480 / 2);
  const io::InstanceMask mask = io::readInstanceMask((out / "robot0" / "instances" / "000001.png").string());
  EXPECT_EQ(mask.class_id.size(), mask.object_id.size());
  for (int obj : mask.object_id) EXPECT_GE(obj, 1);
  fs::remove_all(out);
}

TEST(Dataset, MixedTeamGivesEachRobotItsOwnSensorAndMotion) {
  simulator::ScenarioSpec spec;
  spec.world = "forest";
  spec.forest.num_trees = 150;
  spec.robots = 3;
  spec.frames = 2;
  spec.aerial_robots = {2};
  const simulator::Scenario sc = simulator::buildScenario(spec);
  const fs::path out = scratch("mixed");
  simulator::SensorOptions sensors;
  sensors.per_robot = {"lidar", "rgbd", "rgbd"};
  simulator::writeScenarioDataset(sc, sensors, out.string());
  EXPECT_EQ(io::openRobotDataset((out / "robot0").string()).sensor, io::RobotDataset::Sensor::Lidar);
  EXPECT_EQ(io::openRobotDataset((out / "robot1").string()).sensor, io::RobotDataset::Sensor::Rgbd);
  EXPECT_EQ(io::openRobotDataset((out / "robot2").string()).sensor, io::RobotDataset::Sensor::Rgbd);
  for (int r = 0; r < 3; ++r) {
    std::ifstream yaml(out / ("robot" + std::to_string(r)) / "robot.yaml");
    const std::string text((std::istreambuf_iterator<char>(yaml)), {});
    EXPECT_NE(text.find(r == 2 ? "aerial: true" : "aerial: false"), std::string::npos) << text;
  }
  // A sensor list that does not cover the team is an error, not a silent default.
  sensors.per_robot = {"lidar", "rgbd"};
  EXPECT_THROW(simulator::writeScenarioDataset(sc, sensors, scratch("mixed_short").string()), std::invalid_argument);
  fs::remove_all(out);
  fs::remove_all(scratch("mixed_short"));
}

TEST(Dataset, EveryWorldForOneToThreeRobots) {
  const bool kitti = fs::exists(std::string(SLIDE_DATA_DIR) + "/kitti/poses/05.txt");
  int robots = 1;
  for (const std::string& world : simulator::worldNames()) {
    if (world.rfind("kitti", 0) == 0 && !kitti) continue;
    SCOPED_TRACE(world);
    simulator::ScenarioSpec spec;
    spec.world = world;
    spec.robots = robots;
    spec.frames = 2;
    const simulator::Scenario sc = simulator::buildScenario(spec);
    ASSERT_EQ(sc.robots.size(), static_cast<std::size_t>(robots));
    const fs::path out = scratch("world_" + world);
    simulator::SensorOptions sensors;
    sensors.lidar = simulator::lidarModel("vlp-16");
    simulator::writeScenarioDataset(sc, sensors, out.string());
    EXPECT_EQ(io::readGroundTruthObjects((out / "objects.csv").string()).size(), sc.world.objects.size());
    for (int r = 0; r < robots; ++r) {
      const io::RobotDataset d = io::openRobotDataset((out / ("robot" + std::to_string(r))).string());
      ASSERT_EQ(d.size(), 2u);
      EXPECT_GT(d.scan(1).size(), 1000u);
    }
    fs::remove_all(out);
    robots = robots % 3 + 1;
  }
}

TEST(Dataset, SimulatedMissionAsABagGivesTheDriverTheSameFramesAndPoses) {
  // The folder written as a bag (tools/convert/folder_to_bag.py, python3-rosbag) must reach the
  // daemons unchanged: same frames, points and odometry, so the same map comes out of either.
  simulator::ScenarioSpec spec;
  spec.world = "forest";
  spec.robots = 1;
  spec.frames = 5;
  const simulator::Scenario sc = simulator::buildScenario(spec);
  const fs::path out = scratch("asbag");
  simulator::SensorOptions sensors;
  sensors.lidar = simulator::lidarModel("vlp-16");
  simulator::writeScenarioDataset(sc, sensors, out.string());
  const std::string bag = (out / "robot0.bag").string();
  const std::string cmd = "/usr/bin/python3 " + std::string(SLIDE_SOURCE_DIR) + "/tools/convert/folder_to_bag.py " +
                          (out / "robot0").string() + " " + bag + " --t0 1700000000 > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const io::RobotDataset folder = io::openRobotDataset((out / "robot0").string());
  io::DatasetOptions o;
  o.bag.cloud_topic = "/points";
  o.bag.odom_topic = "/odom";
  const io::RobotDataset fromBag = io::openRobotDataset(bag, o);
  ASSERT_EQ(fromBag.size(), folder.size());
  for (std::size_t i = 0; i < folder.size(); ++i) {
    EXPECT_NEAR(fromBag.times[i] - 1700000000.0, folder.times[i], 1e-6);
    EXPECT_TRUE(fromBag.odometry[i].pose.isApprox(folder.odometry[i].pose, 1e-6));
    const io::LabelledScan a = folder.scan(i), b = fromBag.scan(i);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      ASSERT_EQ(a.xyz[k], b.xyz[k]);
      ASSERT_EQ(a.intensity[k], b.intensity[k]);
    }
  }
  fs::remove_all(out);
}
