#pragma once
// A key-pose bundle as the team layer sees it: what keypose_bundle_t carries, plus whether it
// is the first bundle of its origin (so receivers know where per-origin delivery starts).
#include <array>
#include <cstdint>
#include <vector>

#include "objects/object.h"

namespace slide::team {

struct Bundle {
  std::int32_t origin = 0;  // robot that observed it
  std::int32_t seq = 0;     // its key-pose sequence number at that robot
  bool first = false;       // no earlier bundle of this origin exists
  // Seqs seq-gap..seq-1 of this origin never reached its peer sync (lost on the robot bus) and
  // never will: receivers hold them as absent, so delivery goes on (the back-end bridges the
  // gap with the odometry poses). Team layer only, not on keypose_bundle_t.
  std::int32_t gap = 0;
  std::int64_t utime = 0;
  Pose odom_pose = Pose::Identity();
  Pose relative_odom = Pose::Identity();  // motion since key pose seq-1, in that pose's frame
  std::array<float, 6> odom_sigma{};      // x y z roll pitch yaw
  std::vector<Object> objects;            // in this key pose's body frame
};

// A robot's object map as shared for place recognition.
struct SharedMap {
  std::int32_t robot = 0;        // who built it
  std::int32_t frame_robot = 0;  // whose frame it is expressed in
  std::int32_t version = 0;
  std::int64_t utime = 0;
  std::vector<Object> objects;
};

}  // namespace slide::team
