#pragma once
// One key pose's observation, as every stage carries it (the tracker makes it, peer sync shares
// it, the back-end adds it to the graph; keypose_bundle_t without LCM, msg/convert.h): (robot,
// seq) identifies it team-wide; relative_odom is the motion since key pose seq-1 in that pose's
// body frame; objects are in this key pose's body frame.
// Vocabulary: in namespace slide itself, not slide::objects, as every area uses it (README).
#include <cstdint>
#include <vector>

#include "objects/object.h"

namespace slide {

struct KeyPoseBundle {
  int robot = 0;                          // the robot that observed it (the team layer's origin)
  int seq = 0;                            // 0, 1, 2, ... per robot
  std::int64_t utime = 0;
  Pose odom_pose = Pose::Identity();      // T_odom_body, in the robot's own odometry frame
  Pose relative_odom = Pose::Identity();  // from key pose seq-1 to this one (identity for seq 0)
  Vector6d odom_sigma = Vector6d::Zero();  // x y z roll pitch yaw; zeros: unknown
  std::vector<Object> objects;            // body frame; the tracker's ids are track ids

  // Delivery facts of the team layer (peer sync, its codec and journal); not on keypose_bundle_t.
  bool first = false;     // no earlier bundle of this robot exists
  // Seqs seq-gap..seq-1 of this robot never reached its peer sync (lost on the robot bus) and
  // never will: receivers hold them as absent, so delivery goes on (the back-end bridges the
  // gap with the odometry poses).
  std::int32_t gap = 0;
};

}  // namespace slide
