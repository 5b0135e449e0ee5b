#include "frontend/point_stats.h"
#include "frontend/shape_fit.h"

namespace slide {

std::optional<Ellipsoid> fitEllipsoid(const Cloud& pts, const EllipsoidFitParams& p, const Eigen::Vector3d& viewpoint,
                                      std::string* why) {
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
  const Eigen::Vector2d box_centre(0.5 * (quantileInPlace(xs, p.low_percentile) + quantileInPlace(xs, p.high_percentile)),
                                   0.5 * (quantileInPlace(ys, p.low_percentile) + quantileInPlace(ys, p.high_percentile)));
  Eigen::Vector2d centre = box_centre;
  // A partial view: the points are the side that faces the viewpoint, so the middle of their
  // depth span lies short of the object's centre. In the frame of the horizontal ray from the
  // viewpoint, the object is taken as deep as it is wide across the ray (a round body of
  // unknown orientation) and its centre as that depth's middle behind the nearest points.
  // Seen all round (a track's points from many viewpoints, porous vegetation) the depth span
  // already matches the width and nothing moves.
  const Eigen::Vector2d ray = box_centre - viewpoint.head<2>();
  if (ray.norm() > 1e-6) {
    const Eigen::Vector2d u = ray.normalized(), v(-u.y(), u.x());
    std::vector<double> along, across;
    for (const auto& q : pts) {
      const Eigen::Vector2d d = q.head<2>().cast<double>() - box_centre;
      along.push_back(d.dot(u));
      across.push_back(d.dot(v));
    }
    const double near = quantileInPlace(along, p.low_percentile), far = quantileInPlace(along, p.high_percentile);
    const double left = quantileInPlace(across, p.low_percentile), right = quantileInPlace(across, p.high_percentile);
    const double depth = std::max(far - near, right - left);
    centre = box_centre + u * (near + 0.5 * depth) + v * (0.5 * (left + right));
  }
  std::vector<double> r;
  for (const auto& q : pts) r.push_back((q.head<2>().cast<double>() - centre).norm());
  Ellipsoid e;
  e.centroid = Eigen::Vector3d(centre.x(), centre.y(), 0.5 * (lo_z + hi_z));
  e.radius = std::max(quantileInPlace(r, p.radius_percentile), 0.01);
  e.height = std::max(hi_z - lo_z, 0.01);
  return e;
}

}  // namespace slide
