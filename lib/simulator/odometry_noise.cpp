#include "simulator/odometry_noise.h"

#include <cmath>

namespace slide::simulator {

Pose odometryOrigin(const Pose& T0) {
  const Eigen::Vector3d t = T0.translation();
  return poseFromXyzYaw(t.x(), t.y(), t.z(), yawOf(T0.linear()));
}

std::vector<Pose> simulateOdometry(const std::vector<Pose>& gt, const OdometryNoise& n, std::mt19937_64& rng) {
  std::vector<Pose> out;
  if (gt.empty()) return out;
  std::normal_distribution<double> n01(0.0, 1.0);
  const double deg = M_PI / 180.0;
  // Biases: scale error and lateral slip (fractions of distance), yaw rate (rad/m), climb (m/m).
  double scale_bias = n.translation_drift * n01(rng);
  double lateral_bias = 0.5 * n.translation_drift * n01(rng);
  double yaw_bias = n.yaw_drift_deg_per_m * deg * n01(rng);
  double z_bias = n.vertical_drift * n01(rng);

  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  double yaw = 0;
  for (std::size_t k = 0; k < gt.size(); ++k) {
    if (k > 0) {
      const Eigen::Vector3d dp_w = gt[k].translation() - gt[k - 1].translation();
      const double yaw_prev = yawOf(gt[k - 1].linear());
      const Eigen::Vector3d dp = rotZ(yaw_prev).transpose() * dp_w;  // in the previous heading frame
      const double dyaw = wrapAngle(yawOf(gt[k].linear()) - yaw_prev);
      const double d = dp.norm();
      const double walk = n.bias_walk * std::sqrt(d / 100.0);
      scale_bias += walk * n.translation_drift * n01(rng);
      lateral_bias += walk * 0.5 * n.translation_drift * n01(rng);
      yaw_bias += walk * n.yaw_drift_deg_per_m * deg * n01(rng);
      z_bias += walk * n.vertical_drift * n01(rng);
      const double white = 0.3 * n.translation_drift * std::sqrt(d);
      Eigen::Vector3d dp_noisy = dp * (1.0 + scale_bias);
      dp_noisy.y() += lateral_bias * d + white * n01(rng);
      dp_noisy.x() += white * n01(rng);
      dp_noisy.z() += z_bias * d + 0.3 * n.vertical_drift * std::sqrt(d) * n01(rng);
      const double dyaw_noisy = dyaw + yaw_bias * d + 0.3 * n.yaw_drift_deg_per_m * deg * std::sqrt(d) * n01(rng);
      p += rotZ(yaw) * dp_noisy;
      yaw = wrapAngle(yaw + dyaw_noisy);
    }
    const Eigen::Vector3d rpy = rpyOf(gt[k].linear());
    double roll = rpy[0], pitch = rpy[1];
    roll += n.roll_pitch_noise_deg * deg * n01(rng);
    pitch += n.roll_pitch_noise_deg * deg * n01(rng);
    out.push_back(poseFromXyzRpy(p, roll, pitch, yaw));
  }
  return out;
}

}  // namespace slide::simulator
