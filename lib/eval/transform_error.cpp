#include "eval/transform_error.h"

#include <algorithm>
#include <cmath>

namespace slide {

TransformError transformError(const Pose& estimate, const Pose& truth) {
  TransformError e;
  e.translation_m = (estimate.translation() - truth.translation()).norm();
  e.yaw_deg = std::abs(wrapAngle(yawOf(estimate.linear()) - yawOf(truth.linear()))) * 180.0 / M_PI;
  const Eigen::Matrix3d dR = truth.linear().transpose() * estimate.linear();
  e.rotation_deg = std::acos(std::clamp((dR.trace() - 1.0) / 2.0, -1.0, 1.0)) * 180.0 / M_PI;
  return e;
}

}  // namespace slide
