// Ellipsoid (centroid) range-bearing functor.
#include <ceres/autodiff_cost_function.h>
#include <ceres/numeric_diff_cost_function.h>

#include "backend/factors.h"
#include "backend/se3_jet.h"

namespace slide::backend {

namespace {

struct EllipsoidError {
  EllipsoidError(const Eigen::Vector3d& c, double range_sigma, double bearing_sigma)
      : range_m(c.norm()), azimuth_m(std::atan2(c.y(), c.x())), elevation_m(std::atan2(c.z(), c.head<2>().norm())),
        inv_range_sigma(1.0 / range_sigma), inv_bearing_sigma(1.0 / bearing_sigma) {}

  template <typename T>
  bool operator()(const T* body, const T* centroid, T* residual) const {
    using V = jet::Vec3<T>;
    const V p = jet::toBody(body, V(Eigen::Map<const V>(centroid)));
    const T horizontal = sqrt(p.x() * p.x() + p.y() * p.y() + T(1e-12));
    const T range = sqrt(horizontal * horizontal + p.z() * p.z());
    const T azimuth_diff = atan2(p.y(), p.x()) - azimuth_m;
    residual[0] = (range - range_m) * inv_range_sigma;
    residual[1] = atan2(sin(azimuth_diff), cos(azimuth_diff)) * inv_bearing_sigma;
    residual[2] = (atan2(p.z(), horizontal) - elevation_m) * inv_bearing_sigma;
    return true;
  }

  double range_m, azimuth_m, elevation_m;
  double inv_range_sigma, inv_bearing_sigma;
};

}  // namespace

ceres::CostFunction* ellipsoidFactor(const Eigen::Vector3d& centroid_in_body, double range_sigma, double bearing_sigma,
                                     Differentiation d) {
  auto* f = new EllipsoidError(centroid_in_body, range_sigma, bearing_sigma);
  if (d == Differentiation::Numeric)
    return new ceres::NumericDiffCostFunction<EllipsoidError, ceres::CENTRAL, 3, 7, 3>(f);
  return new ceres::AutoDiffCostFunction<EllipsoidError, 3, 7, 3>(f);
}

}  // namespace slide::backend
