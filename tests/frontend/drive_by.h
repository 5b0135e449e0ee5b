#pragma once
// The drive the front-end daemon tests replay past a synthetic scene: frame k at 10 Hz,
// 0.4 m along x per frame, the sensor 1.5 m up; its header and odometry message.
#include "msg/convert.h"
#include "slide/header_t.hpp"
#include "slide/odometry_t.hpp"

namespace slide::testing {

inline Pose driveByPose(int k) { return poseFromXyzYaw(0.4 * k, 0, 1.5, 0); }

inline header_t driveByHeader(int k) {
  header_t h;
  h.utime = 1000000 + k * 100000;
  h.robot = 0;
  h.seq = k;
  return h;
}

inline odometry_t driveByOdometry(int k) {
  odometry_t m{};
  m.header = driveByHeader(k);
  m.pose = msg::toLcm(driveByPose(k));
  return m;
}

}  // namespace slide::testing
