#pragma once
// 4-DoF (x, y, z, yaw) least squares between matched landmarks: roll and pitch are known
// from the IMU, so T_a_b = [Rz(yaw) | t] minimizing sum w_i |a_i - (Rz b_i + t)|^2.
#include <vector>

#include "geometry/pose.h"

namespace slide::place {

struct Alignment {
  bool ok = false;               // false for fewer than two distinct points or zero weights
  Pose T_a_b = Pose::Identity();
  std::vector<double> residuals;  // |a_i - T b_i| per pair, metres
  double rms = 0;                // root mean square of residuals (unweighted)
};

// Closed form: weighted centroids, yaw = atan2(sum w (b' x a')_z, sum w b'.a'), t = ca - R cb.
// `weights` empty means all ones.
Alignment alignXyzYaw(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                      const std::vector<double>& weights = {});

// Closed form, then iteratively reweighted least squares with Cauchy weights of scale `c`
// (metres): residuals much larger than c stop pulling the estimate.
Alignment alignXyzYawRobust(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                            double c = 0.3, int iterations = 10);

}  // namespace slide::place
