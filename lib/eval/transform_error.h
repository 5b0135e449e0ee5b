#pragma once
// Error of an estimated rigid transform (e.g. an inter-robot frame transform from place
// recognition) against the true one.
#include "geometry/pose.h"

namespace slide::eval {

struct TransformError {
  double translation_m = 0;  // |t_est - t_true|
  double yaw_deg = 0;        // |wrap(yaw_est - yaw_true)|, ZYX yaw
  double rotation_deg = 0;   // angle of inv(R_true) R_est (all three axes)
};

TransformError transformError(const Pose& estimate, const Pose& truth);

}  // namespace slide::eval
