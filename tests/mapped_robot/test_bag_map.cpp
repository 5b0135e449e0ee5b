// A simulated mission written as a ROS 1 bag (tools/convert/folder_to_bag.py) gives the same
// object map as the same mission read from its folder: both recordings go through what the
// daemons run on a label-free robot (the geometric segmenter, the tracker's key-pose bundler,
// the back-end optimizer), in one process, and the two maps are compared object by object.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "backend/optimizer.h"
#include "frontend/frontend_config.h"
#include "frontend/geometric_segmenter.h"
#include "frontend/keypose.h"
#include "io/robot_dataset.h"
#include "simulator/dataset_writer.h"

using namespace slide;
namespace fs = std::filesystem;

namespace {
constexpr double kT0 = 1700000000.0;  // folder_to_bag.py's --t0

struct MapResult {
  std::vector<Object> objects;
  int bundles = 0;
};

// The recording's frames as the driver publishes them (raw points, odometry at the frame's
// time, microsecond stamps relative to `t0`) through segmenter, tracker and optimizer.
MapResult mapOf(const io::RobotDataset& d, double t0) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig fe = frontend::loadDefaultFrontendConfig();
  const frontend::GeometricSegmenter segmenter(classes, fe.geometric);
  frontend::KeyPoseBundler bundler(frontend::Tracker(classes, fe.tracker, fe.fit), fe.keypose);
  // One solver thread: two-thread full solves sum in varying order and differ by ~1e-5 m from
  // run to run, which would hide whether the inputs were the same.
  backend::BackendConfig backend = backend::loadBackendConfig(std::string(SLIDE_SOURCE_DIR) + "/config/backend.yaml");
  backend.num_threads = 1;
  backend::Optimizer optimizer(backend, classes, 0);
  MapResult out;
  for (std::size_t i = 0; i < d.size(); ++i) {
    io::LabelledScan scan = d.scan(i);
    scan.semantic.clear(), scan.instance.clear();  // a real robot's input: no ground-truth labels
    frontend::InputIssues issues;
    frontend::FrameInstances fi;
    fi.utime = std::llround((d.times[i] - t0) * 1e6);
    fi.odom_pose = d.odometry[i].pose;
    fi.instances = segmenter.segment(scan, issues);
    if (const auto bundle = bundler.process(fi, issues)) {
      optimizer.addBundle(*bundle);
      ++out.bundles;
    }
  }
  optimizer.fullSolve();
  out.objects = optimizer.landmarks(true);
  return out;
}
}  // namespace

TEST(BagMap, SimulatedMissionAsABagGivesTheSameMapAsItsFolder) {
  simulator::ScenarioSpec spec;
  spec.world = "forest";
  spec.robots = 1;
  spec.distance = 25;
  spec.rate = 2;
  spec.seed = 3;
  const simulator::Scenario sc = simulator::buildScenario(spec);
  const fs::path out = fs::temp_directory_path() / ("slide_test_bag_map_" + std::to_string(::getpid()));
  fs::remove_all(out);
  simulator::SensorOptions sensors;
  sensors.lidar = simulator::lidarModel("vlp-16");
  simulator::writeScenarioDataset(sc, sensors, out.string());
  const std::string bag = (out / "robot0.bag").string();
  const std::string cmd = "/usr/bin/python3 " + std::string(SLIDE_SOURCE_DIR) + "/tools/convert/folder_to_bag.py " +
                          (out / "robot0").string() + " " + bag + " --t0 " + std::to_string(kT0) + " > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  io::DatasetOptions o;
  o.bag.cloud_topic = "/points";
  o.bag.odom_topic = "/odom";
  const io::RobotDataset folder = io::openRobotDataset((out / "robot0").string());
  const io::RobotDataset from_bag = io::openRobotDataset(bag, o);
  ASSERT_EQ(from_bag.size(), folder.size());
  // The inputs agree to rounding: the same odometry at every frame ...
  for (std::size_t i = 0; i < folder.size(); ++i) {
    ASSERT_LT((from_bag.odometry[i].pose.translation() - folder.odometry[i].pose.translation()).norm(), 1e-6) << i;
    ASSERT_NEAR(from_bag.times[i] - kT0, folder.times[i], 1e-6) << i;
  }

  const MapResult a = mapOf(folder, 0.0), b = mapOf(from_bag, kT0);
  fs::remove_all(out);
  RecordProperty("objects", static_cast<int>(a.objects.size()));
  RecordProperty("bundles", a.bundles);
  EXPECT_GE(a.bundles, 5);
  ASSERT_GE(a.objects.size(), 5u) << "too small a map to compare";
  EXPECT_EQ(b.bundles, a.bundles);
  ASSERT_EQ(b.objects.size(), a.objects.size());
  for (std::size_t k = 0; k < a.objects.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(b.objects[k].class_id, a.objects[k].class_id);
    EXPECT_EQ(b.objects[k].shape(), a.objects[k].shape());
    EXPECT_EQ(b.objects[k].num_observations, a.objects[k].num_observations);
    // ... and the maps to 0.1 mm: the solve amplifies the inputs' rounding (bag stamps are
    // nanoseconds from t0, the folder's seconds from 0) to ~1e-5 m; a wrong stamp or pose
    // would move objects by centimetres.
    EXPECT_LT((b.objects[k].position() - a.objects[k].position()).norm(), 1e-4);
    EXPECT_LT((b.objects[k].extent() - a.objects[k].extent()).norm(), 1e-4);
  }
}
