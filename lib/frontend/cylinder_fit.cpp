#include <algorithm>
#include <cmath>

#include "frontend/point_stats.h"
#include "frontend/shape_fit.h"

namespace slide::frontend {

namespace {
struct SliceFit {
  double z = 0;  // slice middle
  Eigen::Vector2d center;
  double radius = 0;
  double weight = 0;
  bool circle = false;  // center/radius from a circle fit (else from the point spread)
};

void setWhy(std::string* why, const std::string& s) {
  if (why) *why = s;
}

// Axis line x = a + b (z - z0), y = c + d (z - z0) through slice centres (weighted LS); upright
// through their weighted mean when the slices span less than min_span.
void fitAxis(const std::vector<SliceFit>& s, double z0, double min_span, Eigen::Vector2d& base, Eigen::Vector2d& slope) {
  double sw = 0, sz = 0, szz = 0;
  Eigen::Vector2d sp = Eigen::Vector2d::Zero(), spz = Eigen::Vector2d::Zero();
  for (const auto& f : s) {
    const double w = f.weight, dz = f.z - z0;
    sw += w;
    sz += w * dz;
    szz += w * dz * dz;
    sp += w * f.center;
    spz += w * dz * f.center;
  }
  const double det = sw * szz - sz * sz;
  const auto [lo, hi] = std::minmax_element(s.begin(), s.end(), [](const SliceFit& a, const SliceFit& b) { return a.z < b.z; });
  if (s.size() < 2 || det < 1e-9 * std::max(1.0, sw * sw) || hi->z - lo->z < min_span) {
    base = sp / sw;
    slope.setZero();
    return;
  }
  slope = (sw * spz - sz * sp) / det;
  base = (sp - slope * sz) / sw;
}
}  // namespace

// One attempt at a fixed slice height (defined below).
std::optional<Cylinder> fitCylinderOnce(const Cloud& pts, const CylinderFitParams& p, const Eigen::Vector3d& viewpoint,
                                        std::string* why);

std::optional<Cylinder> fitCylinder(const Cloud& pts, const CylinderFitParams& p, const Eigen::Vector3d& viewpoint,
                                    std::string* why) {
  // Sparse (distant) trunks: when no slice holds enough points, thicker slices are tried.
  CylinderFitParams q = p;
  for (int attempt = 0; attempt < 3; ++attempt, q.slice_height *= 2) {
    std::string reason;
    auto c = fitCylinderOnce(pts, q, viewpoint, &reason);
    if (c) return c;
    setWhy(why, reason);
    if (reason != "no slice with enough points") break;
  }
  return std::nullopt;
}

std::optional<Cylinder> fitCylinderOnce(const Cloud& pts, const CylinderFitParams& p, const Eigen::Vector3d& viewpoint,
                                        std::string* why) {
  if (static_cast<int>(pts.size()) < p.min_points) {
    setWhy(why, "too few points (" + std::to_string(pts.size()) + ")");
    return std::nullopt;
  }
  std::vector<double> zs;
  zs.reserve(pts.size());
  for (const auto& q : pts) zs.push_back(q.z());
  const double z_low = quantileInPlace(zs, 0.01);
  const double z_high = quantileInPlace(zs, 0.99);
  const double top = std::min(z_high, z_low + p.max_height);
  const int num_slices = std::max(1, static_cast<int>(std::ceil((top - z_low) / p.slice_height)));
  std::vector<std::vector<Eigen::Vector2d>> slices(num_slices);
  for (const auto& q : pts) {
    const int k = static_cast<int>((q.z() - z_low) / p.slice_height);
    if (k >= 0 && k < num_slices) slices[k].emplace_back(q.x(), q.y());
  }

  std::vector<SliceFit> fits;
  for (int k = 0; k < num_slices; ++k) {
    const auto& s = slices[k];
    if (static_cast<int>(s.size()) < p.min_slice_points) continue;
    SliceFit f;
    f.z = z_low + (k + 0.5) * p.slice_height;
    // Spread estimate (kept when no circle fits the slice): the radius from the robust width
    // across the viewing direction, the centre from the depths of the visible near-side arc.
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& q : s) mean += q;
    mean /= static_cast<double>(s.size());
    Eigen::Vector2d ray = mean - viewpoint.head<2>();
    ray = ray.norm() > 1e-6 ? Eigen::Vector2d(ray.normalized()) : Eigen::Vector2d::UnitX();
    const Eigen::Vector2d across(-ray.y(), ray.x());
    std::vector<double> lateral, depth;
    for (const auto& q : s) {
      lateral.push_back((q - mean).dot(across));
      depth.push_back((q - mean).dot(ray));
    }
    std::vector<double> tmp = lateral;  // quantileInPlace reorders
    const double spread_r =
        std::max(p.ransac.min_radius, 0.5 * (quantileInPlace(tmp, 0.95) - quantileInPlace(tmp, 0.05)));
    // Each return on the visible half circle, x across the line of sight from its middle, says
    // the centre lies sqrt(r^2 - x^2) behind it; the median of what the returns say is moved
    // neither by range noise (a near quantile moves towards the sensor with it) nor by a few
    // returns from behind. Returns spread evenly across the circle (beams or pixels evenly
    // spaced): the 5th-95th percentile width is 0.9 of the diameter.
    const double r_est = spread_r / 0.9;
    std::vector<double> says;
    says.reserve(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
      const double x = std::min(std::abs(lateral[i]), r_est);
      says.push_back(depth[i] + std::sqrt(r_est * r_est - x * x));
    }
    f.center = mean + ray * quantileInPlace(says, 0.5);
    f.radius = spread_r;
    f.weight = static_cast<double>(s.size());
    auto c = fitCircleRansac(s, p.ransac);
    if (c && c->inliers >= p.min_inlier_ratio * s.size() && c->radius <= 1.5 * spread_r + 0.03) {
      f.center = c->center;
      f.radius = c->radius;
      f.weight = c->inliers;
      f.circle = true;
    }
    fits.push_back(f);
  }
  if (fits.empty()) {
    setWhy(why, "no slice with enough points");
    return std::nullopt;
  }

  Eigen::Vector2d base, slope;
  fitAxis(fits, z_low, p.min_axis_span, base, slope);
  if (fits.size() >= 4) {  // drop the worst slice once when it is far off the axis
    std::size_t worst = 0;
    double worst_d = 0;
    for (std::size_t i = 0; i < fits.size(); ++i) {
      const double d = (fits[i].center - (base + slope * (fits[i].z - z_low))).norm();
      if (d > worst_d) worst_d = d, worst = i;
    }
    if (worst_d > 0.1) {
      fits.erase(fits.begin() + static_cast<long>(worst));
      fitAxis(fits, z_low, p.min_axis_span, base, slope);
    }
  }
  const double lean_deg = std::atan(slope.norm()) * 180.0 / M_PI;
  if (lean_deg > p.max_lean_deg) {
    setWhy(why, "leaning " + std::to_string(lean_deg) + " deg");
    return std::nullopt;
  }

  // Radius: circle fits near breast height first, then any circle fit, then spread estimates.
  std::vector<double> radii;
  const double breast_z = z_low + p.breast_height;
  for (int pass = 0; pass < 3 && radii.empty(); ++pass) {
    for (const auto& f : fits) {
      const bool near = std::abs(f.z - breast_z) <= p.breast_window;
      if ((pass == 0 && f.circle && near) || (pass == 1 && f.circle) || pass == 2) radii.push_back(f.radius);
    }
  }
  if (radii.empty()) {
    setWhy(why, "no radius estimate");
    return std::nullopt;
  }
  Cylinder cyl;
  cyl.radius = quantileInPlace(radii, 0.5);
  cyl.axis = Eigen::Vector3d(slope.x(), slope.y(), 1.0).normalized();
  cyl.root = Eigen::Vector3d(base.x(), base.y(), z_low);
  cyl.length = std::max(z_high - z_low, 1e-3) / cyl.axis.z();
  return cyl;
}

}  // namespace slide::frontend
