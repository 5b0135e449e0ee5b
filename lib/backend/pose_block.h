#pragma once
// Layout of a pose parameter block in the factor graph: [tx, ty, tz, qx, qy, qz, qw]
// (translation, then Eigen's quaternion storage order). Conversions to and from Pose.
#include <array>

#include "geometry/pose.h"

namespace slide::backend {

using PoseBlock = std::array<double, 7>;

inline PoseBlock toPoseBlock(const Pose& T) {
  const Eigen::Quaterniond q(T.linear());
  return {T.translation().x(), T.translation().y(), T.translation().z(), q.x(), q.y(), q.z(), q.w()};
}

inline Pose fromPoseBlock(const double* b) {
  return poseFromPositionQuaternion({b[0], b[1], b[2]}, Eigen::Quaterniond(b[6], b[3], b[4], b[5]));
}

}  // namespace slide::backend
