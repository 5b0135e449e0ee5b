// Gravity (roll and pitch) prior functor.
#include <ceres/autodiff_cost_function.h>
#include <ceres/numeric_diff_cost_function.h>

#include "backend/factors.h"
#include "backend/se3_jet.h"

namespace slide::backend {

namespace {

// The frame's up direction seen in the body frame: measured (from the odometry's attitude)
// against the pose's. The difference's length is 2 sin(tilt error / 2), the same for any
// tilt; yaw does not enter (three residuals of rank two).
struct GravityError {
  GravityError(const Eigen::Quaterniond& q_measured, double sigma)
      : up_m(q_measured.conjugate() * Eigen::Vector3d::UnitZ()), inv_sigma(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    const jet::Vec3<T> up = jet::rotationOf(pose).conjugate() * jet::Vec3<T>(T(0), T(0), T(1));
    for (int i = 0; i < 3; ++i) residual[i] = (up[i] - T(up_m[i])) * T(inv_sigma);
    return true;
  }

  Eigen::Vector3d up_m;
  double inv_sigma;
};

}  // namespace

ceres::CostFunction* gravityFactor(const Eigen::Quaterniond& measured, double sigma, Differentiation d) {
  auto* f = new GravityError(measured.normalized(), sigma);
  if (d == Differentiation::Numeric) return new ceres::NumericDiffCostFunction<GravityError, ceres::CENTRAL, 3, 7>(f);
  return new ceres::AutoDiffCostFunction<GravityError, 3, 7>(f);
}

}  // namespace slide::backend
