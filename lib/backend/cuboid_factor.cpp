// Cuboid observation functor.
#include <ceres/autodiff_cost_function.h>
#include <ceres/numeric_diff_cost_function.h>

#include "backend/factors.h"
#include "backend/se3_jet.h"

namespace slide::backend {

namespace {

struct CuboidError {
  CuboidError(const Pose& m, const Eigen::Vector3d& dims, const PoseSigma& sigma, const Eigen::Vector3d& dims_sigma)
      : q_m(m.linear()), t_m(m.translation()), dims_m(dims), inv_sigma(sigma.cwiseInverse()),
        inv_dims_sigma(dims_sigma.cwiseInverse()) {}

  template <typename T>
  bool operator()(const T* body, const T* cuboid, const T* dims, T* residual) const {
    const jet::Vec6<T> e = jet::relativePoseError(body, cuboid, q_m, t_m);
    for (int i = 0; i < 6; ++i) residual[i] = e[i] * inv_sigma[i];
    for (int i = 0; i < 3; ++i) residual[6 + i] = (dims[i] - dims_m[i]) * inv_dims_sigma[i];
    return true;
  }

  Eigen::Quaterniond q_m;
  Eigen::Vector3d t_m, dims_m;
  Vector6d inv_sigma;
  Eigen::Vector3d inv_dims_sigma;
};

}  // namespace

ceres::CostFunction* cuboidFactor(const Pose& measured_in_body, const Eigen::Vector3d& measured_dims,
                                  const PoseSigma& pose_sigma, const Eigen::Vector3d& dims_sigma, Differentiation d) {
  auto* f = new CuboidError(measured_in_body, measured_dims, pose_sigma, dims_sigma);
  if (d == Differentiation::Numeric)
    return new ceres::NumericDiffCostFunction<CuboidError, ceres::CENTRAL, 9, 7, 7, 3>(f);
  return new ceres::AutoDiffCostFunction<CuboidError, 9, 7, 7, 3>(f);
}

}  // namespace slide::backend
