// Cylinder observation functor.
#include <ceres/autodiff_cost_function.h>
#include <ceres/numeric_diff_cost_function.h>

#include "backend/factors.h"
#include "backend/se3_jet.h"

namespace slide::backend {

namespace {

struct CylinderError {
  CylinderError(const Eigen::Vector3d& root, const Eigen::Vector3d& axis, double radius, const CylinderNoise& n)
      : root_m(root), axis_m(axis.normalized()), radius_m(radius), noise(n) {}

  template <typename T>
  bool operator()(const T* body, const T* cylinder, T* residual) const {
    using V = jet::Vec3<T>;
    const Eigen::Quaternion<T> q_inv = jet::rotationOf(body).conjugate();
    const V root = jet::toBody(body, V(Eigen::Map<const V>(cylinder)));
    const V axis = q_inv * Eigen::Map<const V>(cylinder + 3);
    const V d = root_m.cast<T>() - root;
    const T along = d.dot(axis);
    const V perpendicular = d - along * axis;
    const V whitened = noise.position_sqrt_info.cast<T>() * perpendicular;
    for (int i = 0; i < 3; ++i) residual[i] = whitened[i];
    residual[3] = along / noise.along_axis_sigma;
    for (int i = 0; i < 3; ++i) residual[4 + i] = (axis[i] - axis_m[i]) / noise.axis_sigma;
    residual[7] = (cylinder[6] - radius_m) / noise.radius_sigma;
    return true;
  }

  Eigen::Vector3d root_m, axis_m;
  double radius_m;
  CylinderNoise noise;
};

}  // namespace

ceres::CostFunction* cylinderFactor(const Eigen::Vector3d& root_in_body, const Eigen::Vector3d& axis_in_body,
                                    double radius, const CylinderNoise& noise, Differentiation d) {
  auto* f = new CylinderError(root_in_body, axis_in_body, radius, noise);
  if (d == Differentiation::Numeric)
    return new ceres::NumericDiffCostFunction<CylinderError, ceres::CENTRAL, 8, 7, 7>(f);
  return new ceres::AutoDiffCostFunction<CylinderError, 8, 7, 7>(f);
}

}  // namespace slide::backend
