#pragma once
// Graph-level scenarios for the back-end: ground-truth landmarks and robot paths turned into
// noisy key-pose bundles (what a front-end would deliver), as plain C++ structs. Each robot's
// odometry frame is its own first pose: bundle 0 has odom_pose = identity, and
// ScenarioRobot::truth[0] maps that frame into the world.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "objects/keypose_bundle.h"
#include "objects/object.h"

namespace slide::graph_scenario {

// Measurement and odometry noise of a simulated robot.
// Cuboids and ellipsoids: range, azimuth and elevation noise on the centre. Cylinders (trunk
// and pole fits): horizontal range and azimuth noise, elevation noise moving them vertically.
struct ScenarioNoise {
  double range_sigma = 0.1;       // metres, on the range to an object's centre
  double bearing_sigma = 0.05;    // radians, on azimuth and elevation
  double odom_fraction = 0.01;    // translation sigma per axis as a fraction of the step
  double odom_yaw_per_m = 0.001;  // yaw sigma per metre of step (radians)
  double odom_tilt_sigma = 0.0009;  // roll/pitch white noise (radians): an IMU keeps them, no drift
  double yaw_sigma = 0.05;        // cuboid heading
  double axis_sigma = 0.02;       // cylinder axis tilt
  double size_sigma = 0.03;       // radius, height, dims
  double range = 15.0;            // sensor range (horizontal distance to the object centre)
  int max_objects = 20;           // nearest objects reported per key pose
};

struct ScenarioRobot {
  int id = 0;
  std::vector<Pose> truth;              // true key poses in the world frame
  std::vector<KeyPoseBundle> bundles;   // noisy, in the robot's odometry frame
  std::vector<std::vector<int>> seen;   // per bundle and object: index into GraphScenario::landmarks
};

// A graph-level scenario: true landmarks and robots' noisy key-pose bundles (sim/scenario.h
// holds the simulator's worlds and robot runs).
struct GraphScenario {
  std::string name;
  std::vector<Object> landmarks;        // true landmarks in the world frame (id = index)
  std::vector<ScenarioRobot> robots;    // robots[0] is the host
  ScenarioNoise noise;
};

// Key poses spaced evenly along a 2-D polyline at height z, heading along the path.
std::vector<Pose> pathAlongWaypoints(const std::vector<Eigen::Vector2d>& waypoints, int num_poses, double z = 0.0);

// One noisy detection of an object given in the body frame (noise model above); keeps its id
// and class.
Object observeObject(const Object& body_truth, const ScenarioNoise& noise, std::mt19937& rng);

// Drives `truth` past `landmarks` and records noisy bundles stamped from `utime0` (0.1 s apart).
ScenarioRobot simulateRobot(int id, const std::vector<Pose>& truth, const std::vector<Object>& landmarks,
                            const ScenarioNoise& noise, std::mt19937& rng, std::int64_t utime0 = 0);

// An intra-robot loop closure as a place-recognition stage would report it once key pose
// seq_b exists: the pose of seq_b's body in seq_a's body, with noise.
struct ScenarioLoopClosure {
  int robot = 0;
  int seq_a = 0, seq_b = 0;
  Pose T_a_b = Pose::Identity();
};

// Loop closures of one robot: whenever it is within `radius` of a true pose at least
// `min_gap` key poses older, at most one per `every` key poses; noise in metres / radians.
std::vector<ScenarioLoopClosure> simulateLoopClosures(const ScenarioRobot& robot, double radius = 4.0,
                                                      int min_gap = 150, int every = 50, double metres = 0.05,
                                                      double radians = 0.005, std::uint32_t seed = 7);

// Indoor: 10 x 20 m room, 150 key poses, 70 furniture ellipsoids, range 4 m.
GraphScenario makeIndoorScenario(std::uint32_t seed = 1);
// Urban: 200 x 200 m, 300 key poses over 715 m, 250 cars/poles/other, range 15 m.
GraphScenario makeUrbanScenario(std::uint32_t seed = 2);
// Forest: 400 x 400 m, 1000 key poses over 1430 m in two loops sharing a re-driven edge,
// 860 trunks within 15 m of the path, range 15 m.
GraphScenario makeForestScenario(std::uint32_t seed = 3);
// A long forest mission: copies of the forest tile (its trunks and route) side by side, 400 m
// apart in x, driven one after the other (each route's end is joined to the next one's start,
// re-driving both tiles' southern edges), at the forest's key-pose spacing; cut to
// `num_keyposes`. The first 1000 key poses drive the forest route.
GraphScenario makeForestChainScenario(int num_keyposes, std::uint32_t seed = 3);
// A long mission that returns to its start: as many chained forest tiles as the key poses
// reach, driven out as makeForestChainScenario does and then back west along y = 100 m (every
// tile's southern edge and the roads between them, all driven before) to the first tile's
// start, which is the last key pose. Revisits: each tile's re-driven shared edge, the whole
// way back, and the start. The spacing is the forest's stretched to fit (by under 4 % from
// 4,000 key poses on; 1,000 key poses are exactly the forest route).
GraphScenario makeForestReturnScenario(int num_keyposes, std::uint32_t seed = 3);
// KITTI: the real LiDAR path of a sequence (poses file, KITTI camera layout) cut into
// `num_robots` consecutive robots, key poses every `spacing` metres, observing the real pole
// map (csv "x,y") as cylinders within 20 m. Throws IoError / std::runtime_error on bad files.
GraphScenario makeKittiScenario(const std::string& name, const std::string& poses_file, const std::string& poles_file,
                           int num_robots = 3, double spacing = 2.0, std::uint32_t seed = 5);

}  // namespace slide::graph_scenario
