#include "simulator/ray_shapes.h"

#include <cmath>
#include <limits>

namespace slide::simulator {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

double intersectRayCylinder(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& root,
                            const Eigen::Vector3d& axis, double radius, double length, double t_min) {
  const Eigen::Vector3d op = o - root;
  const double oa = op.dot(axis), da = d.dot(axis);
  const Eigen::Vector3d o_perp = op - oa * axis, d_perp = d - da * axis;
  double best = kInf;
  const double A = d_perp.squaredNorm();
  if (A > 1e-12) {
    const double B = o_perp.dot(d_perp);
    const double C = o_perp.squaredNorm() - radius * radius;
    const double disc = B * B - A * C;
    if (disc >= 0) {
      const double t = (-B - std::sqrt(disc)) / A;
      const double h = oa + t * da;
      if (t > t_min && h >= 0 && h <= length) best = t;
    }
  }
  if (std::abs(da) > 1e-12) {
    for (double h : {0.0, length}) {
      const double t = (h - oa) / da;
      if (t > t_min && t < best && (o_perp + t * d_perp).squaredNorm() <= radius * radius) best = t;
    }
  }
  return best;
}

double intersectRayBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Matrix3d& R_box_world,
                       const Eigen::Vector3d& centre, const Eigen::Vector3d& half, double t_min) {
  const Eigen::Vector3d ol = R_box_world * (o - centre), dl = R_box_world * d;
  double t0 = -kInf, t1 = kInf;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(dl[i]) < 1e-12) {
      if (std::abs(ol[i]) > half[i]) return kInf;
      continue;
    }
    double a = (-half[i] - ol[i]) / dl[i], b = (half[i] - ol[i]) / dl[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return kInf;
  }
  return t0 > t_min ? t0 : kInf;
}

double intersectRayEllipsoid(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& centre,
                             const Eigen::Vector3d& semi, double t_min) {
  const Eigen::Vector3d os = (o - centre).cwiseQuotient(semi), ds = d.cwiseQuotient(semi);
  const double A = ds.squaredNorm(), B = os.dot(ds), C = os.squaredNorm() - 1;
  const double disc = B * B - A * C;
  if (disc < 0) return kInf;
  const double t = (-B - std::sqrt(disc)) / A;
  return t > t_min ? t : kInf;
}

}  // namespace slide::simulator
