#include "frontend/point_stats.h"
#include "frontend/shape_fit.h"

namespace slide {

std::optional<Ellipsoid> fitEllipsoid(const Cloud& pts, const EllipsoidFitParams& p, std::string* why) {
  if (static_cast<int>(pts.size()) < p.min_points) {
    if (why) *why = "too few points (" + std::to_string(pts.size()) + ")";
    return std::nullopt;
  }
  std::vector<double> xs, ys, zs;
  for (const auto& q : pts) {
    xs.push_back(q.x());
    ys.push_back(q.y());
    zs.push_back(q.z());
  }
  const double lo_z = quantileInPlace(zs, p.low_percentile), hi_z = quantileInPlace(zs, p.high_percentile);
  // Centre of the robust bounding box: less biased towards the visible side than the mean.
  const double cx = 0.5 * (quantileInPlace(xs, p.low_percentile) + quantileInPlace(xs, p.high_percentile));
  const double cy = 0.5 * (quantileInPlace(ys, p.low_percentile) + quantileInPlace(ys, p.high_percentile));
  std::vector<double> r;
  for (const auto& q : pts) r.push_back(std::hypot(q.x() - cx, q.y() - cy));
  Ellipsoid e;
  e.centroid = Eigen::Vector3d(cx, cy, 0.5 * (lo_z + hi_z));
  e.radius = std::max(quantileInPlace(r, p.radius_percentile), 0.01);
  e.height = std::max(hi_z - lo_z, 0.01);
  return e;
}

}  // namespace slide
