#pragma once
// A simulation scenario: a world plus the robots that drive through it, each with its ground
// truth and its own odometry. Built deterministically from a spec and its seed.
#include <string>
#include <vector>

#include "simulator/forest_world.h"
#include "simulator/odometry_noise.h"
#include "simulator/robot_path.h"

namespace slide::simulator {

struct ScenarioSpec {
  std::string world = "forest";  // forest | urban | indoor | kitti05 | kitti07
  int robots = 3;
  uint64_t seed = 1;
  double distance = 300.0;       // metres per robot (procedural worlds)
  int frames = 0;                // > 0: frames per robot instead of a distance
  double overlap = 0.3;          // share of each route on a route common to all robots
  bool aerial = false;           // aerial robots change altitude (ground robots follow terrain)
  std::vector<int> aerial_robots;  // ids of aerial robots in an otherwise ground team (mixed teams)
  double speed = 0;              // m/s; 0: the world's default (forest 1.5, urban 2, indoor 0.8)
  double rate = 10.0;            // sensor frames per second
  double clearance = 0;           // metres kept free around robot paths; 0: world default
  ForestParams forest;           // forest world parameters
  OdometryNoise odometry;
  std::string data_dir;          // real data (KITTI poses/poles, forest inventory); default SLIDE_DATA_DIR
};

struct RobotRun {
  int id = 0;
  Trajectory ground_truth;       // body poses in the world frame
  std::vector<Pose> odometry;    // body poses in the robot's own odometry frame
  Pose T_world_odom = Pose::Identity();  // where that odometry frame lies in the world
  int first_source_frame = 0;    // KITTI scenarios: index of frame 0 in the real sequence
  bool aerial = false;           // flies (altitude changes) rather than following the ground
};

// Whether robot `id` of a spec flies: every robot with `aerial`, else those in aerial_robots.
bool isAerial(const ScenarioSpec& spec, int id);

struct Scenario {
  ScenarioSpec spec;
  World world;
  std::vector<RobotRun> robots;
};

// Names accepted by ScenarioSpec::world.
std::vector<std::string> worldNames();

// The paper's KITTI splits: frame ranges [first, last) of each robot.
std::vector<std::pair<int, int>> kittiSplits(const std::string& world);

// Builds the world, plans routes (clearing objects off them), follows them and simulates
// odometry. Throws std::invalid_argument for a bad spec, IoError for missing real data.
Scenario buildScenario(const ScenarioSpec& spec);

}  // namespace slide::simulator
