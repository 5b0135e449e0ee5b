#include <cmath>

#include "frontend/point_stats.h"
#include "frontend/shape_fit.h"

namespace slide::frontend {

namespace {
// Where one horizontal slice of a round body puts the body's centre, seen from the viewpoint:
// bearing (radians from the reference ray) and horizontal distance.
struct SliceCentre {
  double bearing = 0, distance = 0, sin_half_angle = 0;
};

// A circle of radius r whose centre lies D from the viewpoint shows its nearest point at
// N = D - r and its silhouette at bearings +-a with sin a = r / D, so D = N / (1 - sin a): the
// centre follows from the nearest range and the angular width alone, however much of the
// circle was seen (half of it from one side, or all of it). A flat face of width w at range N
// gives D ~ N + w / 2: a body of unknown shape is taken as deep as it is wide.
SliceCentre sliceCentre(std::vector<double>& bearing, std::vector<double>& range, const EllipsoidFitParams& p) {
  const double lo = quantileInPlace(bearing, p.slice_percentile), hi = quantileInPlace(bearing, 1.0 - p.slice_percentile);
  const double near = quantileInPlace(range, p.low_percentile);
  SliceCentre s;
  s.bearing = 0.5 * (lo + hi);
  // The quantiles of bearings spread evenly over the silhouette (a depth image's columns) lie
  // inside it by slice_percentile of its span on either side.
  const double half = 0.5 * (hi - lo) / (1.0 - 2.0 * p.slice_percentile);
  s.sin_half_angle = std::sin(std::min(half, 0.5 * M_PI));
  s.distance = near / (1.0 - std::min(s.sin_half_angle, p.max_sin_half_angle));
  return s;
}
}  // namespace

std::optional<Ellipsoid> fitEllipsoid(const Cloud& pts, const EllipsoidFitParams& p, const Eigen::Vector3d& viewpoint,
                                      double min_half_depth, std::string* why) {
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
  // A partial view: the points are the side that faces the viewpoint, so their middle lies
  // short of the object's centre. Each horizontal slice of the points (a round body's slices
  // are circles about one vertical axis) gives the centre's bearing and distance from the
  // viewpoint (sliceCentre); the median over the widest slices is the centre. Too few points per
  // slice (a far LiDAR object): all points form one slice. Seen from within its own angular
  // width (the viewpoint amid the points): the box centre.
  const Eigen::Vector2d eye = viewpoint.head<2>();
  const Eigen::Vector2d ray = box_centre - eye;
  if (ray.norm() > 1e-6) {
    const Eigen::Vector2d u = ray.normalized(), v(-u.y(), u.x());
    // At most kMaxSlices slices from the lowest: a received instance with points metres or
    // kilometres apart in height must not make the fit allocate a slice per 10 cm of that.
    constexpr int kMaxSlices = 256;
    const double top = std::min(hi_z, lo_z + kMaxSlices * p.slice_height);
    const int n = std::clamp(static_cast<int>(std::ceil((top - lo_z) / p.slice_height)), 1, kMaxSlices);
    std::vector<std::vector<double>> bearing(n), range(n);
    std::vector<double> all_bearing, all_range;
    for (const auto& q : pts) {
      const Eigen::Vector2d d = q.head<2>().cast<double>() - eye;
      const double b = std::atan2(d.dot(v), d.dot(u)), r = d.norm();
      all_bearing.push_back(b);
      all_range.push_back(r);
      if (q.z() < lo_z || q.z() > top) continue;
      const int k = std::clamp(static_cast<int>((q.z() - lo_z) / p.slice_height), 0, n - 1);
      bearing[k].push_back(b);
      range[k].push_back(r);
    }
    std::vector<SliceCentre> slices;
    for (int k = 0; k < n; ++k)
      if (static_cast<int>(bearing[k].size()) >= p.min_slice_points) slices.push_back(sliceCentre(bearing[k], range[k], p));
    if (slices.empty()) slices.push_back(sliceCentre(all_bearing, all_range, p));
    // The widest slices: a round body's slices narrow towards its top and bottom, where few
    // points reach the silhouette and the bearing quantiles fall short of it.
    double widest = 0;
    for (const auto& c : slices) widest = std::max(widest, c.sin_half_angle);
    std::vector<double> b, d, s;
    for (const auto& c : slices)
      if (c.sin_half_angle >= p.widest_fraction * widest)
        b.push_back(c.bearing), d.push_back(c.distance), s.push_back(c.sin_half_angle);
    if (quantileInPlace(s, 0.5) < p.max_sin_half_angle) {
      // An object cut by the image border or hidden in part behind a nearer one (a table
      // behind its chairs) shows less than its width: its centre lies at least the class's
      // typical half-depth behind its nearest points.
      const double beta = quantileInPlace(b, 0.5);
      const double dist = std::max(quantileInPlace(d, 0.5), quantileInPlace(all_range, p.low_percentile) + min_half_depth);
      centre = eye + dist * (std::cos(beta) * u + std::sin(beta) * v);
    }
  }
  std::vector<double> r;
  for (const auto& q : pts) r.push_back((q.head<2>().cast<double>() - centre).norm());
  Ellipsoid e;
  e.centroid = Eigen::Vector3d(centre.x(), centre.y(), 0.5 * (lo_z + hi_z));
  e.radius = std::max(quantileInPlace(r, p.radius_percentile), 0.01);
  e.height = std::max(hi_z - lo_z, 0.01);
  return e;
}

}  // namespace slide::frontend
