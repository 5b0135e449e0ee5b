// Relative pose (odometry, loop closure), scaled odometry, and prior functors.
#include <ceres/autodiff_cost_function.h>
#include <ceres/numeric_diff_cost_function.h>

#include "backend/factors.h"
#include "backend/se3_jet.h"

namespace slide::backend {

namespace {

struct RelativePoseError {
  RelativePoseError(const Pose& m, const PoseSigma& sigma)
      : q_m(m.linear()), t_m(m.translation()), inv_sigma(sigma.cwiseInverse()) {}

  template <typename T>
  bool operator()(const T* a, const T* b, T* residual) const {
    return whitened(a, b, t_m, residual);
  }

  // With the measured translation `t` (the measurement's, or a function of other blocks).
  template <typename T, typename S>
  bool whitened(const T* a, const T* b, const Eigen::Matrix<S, 3, 1>& t, T* residual) const {
    const jet::Vec6<T> e = jet::relativePoseError(a, b, q_m, t);
    for (int i = 0; i < 6; ++i) residual[i] = e[i] * inv_sigma[i];
    return true;
  }

  Eigen::Quaterniond q_m;
  Eigen::Vector3d t_m;
  Vector6d inv_sigma;
};

// Odometry whose translation is off by an unknown factor (wheel radius, visual scale): the
// step's translation times the robot's scale block before the between error.
struct ScaledOdometryError {
  ScaledOdometryError(const Pose& m, const PoseSigma& sigma) : between(m, sigma) {}

  template <typename T>
  bool operator()(const T* a, const T* b, const T* scale, T* residual) const {
    const jet::Vec3<T> t = between.t_m.cast<T>() * scale[0];
    return between.whitened(a, b, t, residual);
  }

  RelativePoseError between;
};

struct ScalePriorError {
  explicit ScalePriorError(double sigma) : inv_sigma(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* scale, T* residual) const {
    residual[0] = (scale[0] - T(1)) * inv_sigma;
    return true;
  }

  double inv_sigma;
};

struct PosePriorError {
  PosePriorError(const Pose& m, const PoseSigma& sigma) : between(m, sigma) {}

  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    const T origin[7] = {T(0), T(0), T(0), T(0), T(0), T(0), T(1)};
    return between(origin, pose, residual);
  }

  RelativePoseError between;
};

}  // namespace

ceres::CostFunction* relativePoseFactor(const Pose& measured_a_b, const PoseSigma& sigma, Differentiation d) {
  auto* f = new RelativePoseError(measured_a_b, sigma);
  if (d == Differentiation::Numeric)
    return new ceres::NumericDiffCostFunction<RelativePoseError, ceres::CENTRAL, 6, 7, 7>(f);
  return new ceres::AutoDiffCostFunction<RelativePoseError, 6, 7, 7>(f);
}

ceres::CostFunction* scaledOdometryFactor(const Pose& measured_a_b, const PoseSigma& sigma, Differentiation d) {
  auto* f = new ScaledOdometryError(measured_a_b, sigma);
  if (d == Differentiation::Numeric)
    return new ceres::NumericDiffCostFunction<ScaledOdometryError, ceres::CENTRAL, 6, 7, 7, 1>(f);
  return new ceres::AutoDiffCostFunction<ScaledOdometryError, 6, 7, 7, 1>(f);
}

ceres::CostFunction* scalePriorFactor(double sigma, Differentiation d) {
  auto* f = new ScalePriorError(sigma);
  if (d == Differentiation::Numeric) return new ceres::NumericDiffCostFunction<ScalePriorError, ceres::CENTRAL, 1, 1>(f);
  return new ceres::AutoDiffCostFunction<ScalePriorError, 1, 1>(f);
}

ceres::CostFunction* posePriorFactor(const Pose& measured, const PoseSigma& sigma, Differentiation d) {
  auto* f = new PosePriorError(measured, sigma);
  if (d == Differentiation::Numeric)
    return new ceres::NumericDiffCostFunction<PosePriorError, ceres::CENTRAL, 6, 7>(f);
  return new ceres::AutoDiffCostFunction<PosePriorError, 6, 7>(f);
}

}  // namespace slide::backend
