#include "plot/view.h"

#include <cmath>

namespace slide::plot {

namespace {
constexpr double kDeg = M_PI / 180.0;
}

Eigen::Vector3d View::towardsViewer() const {
  const double a = azimuth_deg * kDeg, e = elevation_deg * kDeg;
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

Eigen::Vector2d View::project(const Eigen::Vector3d& p) const {
  const double a = azimuth_deg * kDeg, e = elevation_deg * kDeg;
  const Eigen::Vector3d right(-std::sin(a), std::cos(a), 0.0);
  const Eigen::Vector3d up(-std::sin(e) * std::cos(a), -std::sin(e) * std::sin(a), std::cos(e));
  return {right.dot(p), up.dot(p)};
}

}  // namespace slide::plot
