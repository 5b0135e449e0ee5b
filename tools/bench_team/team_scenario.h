#pragma once
// Synthetic 3-robot key-pose bundle streams for the team benchmark: a world of objects (forest
// trunks, or urban cars, poles and clutter along streets), robots moving ~1.4 m per key pose,
// each key pose seeing the objects within range in its body frame (with measurement noise),
// drifting odometry, tracker-style ids, and each robot's growing object map.
#include <random>
#include <string>
#include <vector>

#include "objects/keypose_bundle.h"
#include "team/shared_map.h"

namespace slide::team::bench {

struct WorldObject {
  Object model;  // in the world frame; id = landmark index
};

struct RobotStream {
  std::int32_t robot = 0;
  std::vector<KeyPoseBundle> bundles;        // seq 0.., in order
  std::vector<SharedMap> maps;        // map after each bundle (own odometry frame)
  double metres = 0;                  // true distance travelled
  Pose start = Pose::Identity();      // true first pose: the odometry frame in the world
};

struct TeamScenario {
  std::string name;
  std::vector<WorldObject> world;
  std::vector<RobotStream> robots;
  std::size_t landmarks_seen = 0;     // distinct world objects seen by any robot
  double mean_objects_per_keypose = 0;
};

// kind: "forest" or "urban". `keyposes` per robot.
TeamScenario makeScenario(const std::string& kind, int robots, int keyposes, std::uint64_t seed);

}  // namespace slide::team::bench
