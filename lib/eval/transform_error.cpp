#include "eval/transform_error.h"

#include <algorithm>
#include <cmath>

namespace slide::eval {

TransformError transformError(const Pose& estimate, const Pose& truth) {
  TransformError e;
  e.translation_m = (estimate.translation() - truth.translation()).norm();
  e.yaw_deg = std::abs(wrapAngle(yawOf(estimate.linear()) - yawOf(truth.linear()))) * 180.0 / M_PI;
  const Eigen::Matrix3d dR = truth.linear().transpose() * estimate.linear();
  const Eigen::Vector3d w(dR(2, 1) - dR(1, 2), dR(0, 2) - dR(2, 0), dR(1, 0) - dR(0, 1));
  e.rotation_deg = std::atan2(0.5 * w.norm(), 0.5 * (dR.trace() - 1.0)) * 180.0 / M_PI;
  return e;
}

}  // namespace slide::eval
