#pragma once
// Everything one key pose contributes to the graph, as plain C++ (keypose_bundle_t without
// LCM): (robot, seq) identifies it team-wide; relative_odom is the motion since key pose
// seq-1 in that pose's body frame; objects are in this key pose's body frame.
#include <cstdint>
#include <vector>

#include "objects/object.h"

namespace slide {

struct KeyPoseBundle {
  int robot = 0;
  int seq = 0;
  std::int64_t utime = 0;
  Pose odom_pose = Pose::Identity();      // in the robot's own odometry frame
  Pose relative_odom = Pose::Identity();  // from key pose seq-1 to this one
  Vector6d odom_sigma = Vector6d::Zero();  // x y z roll pitch yaw; zeros: unknown
  std::vector<Object> objects;
};

}  // namespace slide
