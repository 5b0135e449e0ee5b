#include "frontend/geometric_segmenter.h"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <unordered_map>

#include "frontend/point_stats.h"

namespace slide {

namespace {
// Points bucketed on a 2-D grid for neighbourhood look-ups around a column axis.
class PlanarBuckets {
 public:
  PlanarBuckets(const Cloud& cloud, const std::vector<int>& idx, double cell) : cloud_(cloud), inv_(1.0 / cell) {
    for (int i : idx) buckets_[key(cloud[i].x(), cloud[i].y())].push_back(i);
  }
  // Indices of points within `radius` (horizontal) of c.
  std::vector<int> near(const Eigen::Vector2d& c, double radius) const {
    std::vector<int> out;
    const long x0 = std::lround(std::floor((c.x() - radius) * inv_)), x1 = std::lround(std::floor((c.x() + radius) * inv_));
    const long y0 = std::lround(std::floor((c.y() - radius) * inv_)), y1 = std::lround(std::floor((c.y() + radius) * inv_));
    for (long x = x0; x <= x1; ++x)
      for (long y = y0; y <= y1; ++y) {
        const auto it = buckets_.find(pack(x, y));
        if (it == buckets_.end()) continue;
        for (int i : it->second)
          if (std::hypot(cloud_[i].x() - c.x(), cloud_[i].y() - c.y()) <= radius) out.push_back(i);
      }
    return out;
  }

 private:
  static std::int64_t pack(long x, long y) { return (static_cast<std::int64_t>(x) << 32) ^ (y & 0xffffffffLL); }
  std::int64_t key(float x, float y) const {
    return pack(std::lround(std::floor(x * inv_)), std::lround(std::floor(y * inv_)));
  }
  const Cloud& cloud_;
  double inv_;
  std::unordered_map<std::int64_t, std::vector<int>> buckets_;
};

struct Footprint {
  double length = 0, width = 0;
};

Footprint footprintOf(const Cloud& cloud, const std::vector<int>& idx) {
  std::vector<cv::Point2f> pts;
  pts.reserve(idx.size());
  for (int i : idx) pts.emplace_back(cloud[i].x(), cloud[i].y());
  const cv::RotatedRect r = cv::minAreaRect(pts);
  return {std::max(r.size.width, r.size.height), std::min(r.size.width, r.size.height)};
}

// Median second difference of ranges over consecutive scan-order triplets in the cluster;
// NaN when there are too few.
double roughness(const Cloud& cloud, const std::vector<int>& idx, std::vector<int>& mark, int label) {
  for (int i : idx) mark[i] = label;
  std::vector<double> d;
  const int n = static_cast<int>(cloud.size());
  for (int i : idx) {
    if (i == 0 || i + 1 >= n || mark[i - 1] != label || mark[i + 1] != label) continue;
    if ((cloud[i - 1] - cloud[i]).squaredNorm() > 0.25f || (cloud[i + 1] - cloud[i]).squaredNorm() > 0.25f) continue;
    d.push_back(std::abs(double(cloud[i - 1].norm()) - 2.0 * cloud[i].norm() + cloud[i + 1].norm()));
  }
  return d.size() < 10 ? std::nan("") : quantileInPlace(d, 0.5);
}

double quantileOf(const std::vector<float>& values, const std::vector<int>& idx, double q) {
  std::vector<double> v;
  v.reserve(idx.size());
  for (int i : idx) v.push_back(values[i]);
  return quantileInPlace(v, q);
}
}  // namespace

GeometricSegmenter::GeometricSegmenter(ClassTable classes, GeometricSegmenterParams params)
    : classes_(std::move(classes)), params_(params) {
  for (int id : {params_.trunk_class, params_.pole_class, params_.car_class, params_.other_class}) classes_.at(id);
}

std::vector<Instance> GeometricSegmenter::segment(const LabelledScan& scan, InputIssues& issues) const {
  if (scan.size() == 0) {
    issues.count("empty scan");
    return {};
  }
  const Cloud& cloud = scan.xyz;
  long bad = 0;
  for (const auto& p : cloud) bad += !p.allFinite();
  issues.count("non-finite point", bad);

  GroundParams gp = params_.ground;
  gp.max_range = params_.max_range;
  const std::vector<float> h = heightAboveGround(cloud, gp);
  std::vector<int> above;
  above.reserve(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (std::isfinite(h[i]) && h[i] > gp.threshold) above.push_back(static_cast<int>(i));

  std::vector<Instance> out;
  auto emit = [&](int class_id, const std::vector<int>& idx) {
    Instance inst;
    inst.id = static_cast<int>(out.size()) + 1;
    inst.class_id = class_id;
    inst.points.reserve(idx.size());
    for (int i : idx) inst.points.push_back(cloud[i]);
    out.push_back(std::move(inst));
  };
  std::vector<char> taken(cloud.size(), 0);

  // 1. Columns (trunks, poles).
  const ColumnParams& cp = params_.column;
  std::vector<int> band;
  for (int i : above)
    if (h[i] >= cp.band_low && h[i] <= cp.band_high) band.push_back(i);
  const PlanarBuckets buckets(cloud, above, 0.5);
  // Highest elevation angle seen (beyond 3 m): columns need not reach above what is visible.
  double tan_elev = -1e9;
  for (int i : above) {
    const double r = std::hypot(cloud[i].x(), cloud[i].y());
    if (r > 3.0) tan_elev = std::max(tan_elev, cloud[i].z() / r);
  }
  const int num_bins = std::max(1, static_cast<int>(std::ceil((cp.band_high - cp.band_low) / cp.coverage_bin)));
  if (!band.empty()) {
    for (const auto& group : clusterGrid(cloud, band, {cp.cell, true, cp.min_points})) {
      double min_x = 1e30, max_x = -1e30, min_y = 1e30, max_y = -1e30;
      std::vector<char> bins(num_bins, 0);
      Eigen::Vector2d c = Eigen::Vector2d::Zero();
      for (int i : group) {
        min_x = std::min<double>(min_x, cloud[i].x());
        max_x = std::max<double>(max_x, cloud[i].x());
        min_y = std::min<double>(min_y, cloud[i].y());
        max_y = std::max<double>(max_y, cloud[i].y());
        bins[std::min(num_bins - 1, static_cast<int>((h[i] - cp.band_low) / cp.coverage_bin))] = 1;
      }
      if (std::max(max_x - min_x, max_y - min_y) > cp.max_diameter) continue;
      int covered = 0;
      for (char b : bins) covered += b;
      if (covered < cp.min_coverage * num_bins) continue;
      c = {0.5 * (min_x + max_x), 0.5 * (min_y + max_y)};
      const double radius = 0.5 * std::hypot(max_x - min_x, max_y - min_y) + cp.margin;
      // Isolation: a trunk or pole stands free; band points in a ring around it mean a wall
      // or a hedge that the planar clustering cut into pieces.
      int ring = 0;
      for (int i : buckets.near(c, radius + cp.isolation_ring))
        if (h[i] >= cp.band_low && h[i] <= cp.band_high && std::hypot(cloud[i].x() - c.x(), cloud[i].y() - c.y()) > radius + cp.isolation_gap)
          ++ring;
      if (ring > cp.max_ring_fraction * static_cast<double>(group.size())) continue;
      std::vector<int> column;
      double top = 0, ground_z = 0;
      for (int i : buckets.near(c, radius)) {
        if (taken[i] || h[i] > cp.max_height) continue;
        column.push_back(i);
        if (h[i] > top) top = h[i], ground_z = cloud[i].z() - h[i];
      }
      const double ceiling = c.norm() * tan_elev - ground_z - cp.ceiling_margin;
      if (top < std::min(cp.min_top, ceiling)) continue;
      // Canopy: points above the band spreading well beyond the axis.
      int canopy = 0, high = 0;
      for (int i : buckets.near(c, cp.canopy_radius + 2.0)) {
        if (h[i] < cp.min_top) continue;
        ++high;
        if (std::hypot(cloud[i].x() - c.x(), cloud[i].y() - c.y()) > cp.canopy_radius) ++canopy;
      }
      const double band_radius = 0.5 * std::max(max_x - min_x, max_y - min_y);
      const bool trunk = band_radius >= cp.trunk_min_radius ||
                         (high > 0 && canopy >= cp.canopy_min_fraction * (high + static_cast<int>(column.size())));
      for (int i : column) taken[i] = 1;
      emit(trunk ? params_.trunk_class : params_.pole_class, column);
    }
  }

  // 2. Cars: clusters of the untaken points below the height cap.
  const CarParams& kp = params_.car;
  std::vector<int> low;
  for (int i : above)
    if (!taken[i] && h[i] <= kp.height_cap) low.push_back(i);
  if (!low.empty()) {
    std::vector<int> mark(cloud.size(), -1);
    int label = 0;
    for (const auto& cl : clusterGrid(cloud, low, {kp.cell, false, kp.min_points})) {
      const double rough = kp.max_roughness > 0 ? roughness(cloud, cl, mark, label++) : std::nan("");
      if (rough > kp.max_roughness) continue;
      const double top = quantileOf(h, cl, 0.95), bottom = quantileOf(h, cl, 0.05);
      if (top < kp.min_top || top > kp.max_top || bottom > kp.max_bottom) continue;
      const Footprint f = footprintOf(cloud, cl);
      if (f.length < kp.min_length || f.length > kp.max_length || f.width > kp.max_width) continue;
      for (int i : cl) taken[i] = 1;
      emit(params_.car_class, cl);
    }
  }

  // 3. Other: remaining compact clusters.
  if (params_.emit_other) {
    std::vector<int> rest;
    for (int i : above)
      if (!taken[i]) rest.push_back(i);
    const ClassInfo& other = classes_.at(params_.other_class);
    if (!rest.empty()) {
      for (const auto& cl : clusterGrid(cloud, rest, params_.other_cluster)) {
        const Footprint f = footprintOf(cloud, cl);
        const double height = quantileOf(h, cl, 0.98) - quantileOf(h, cl, 0.02);
        if (f.length > other.size_max.x() || f.width > other.size_max.y() || height > other.size_max.z()) continue;
        if (f.length < other.size_min.x() && height < other.size_min.z()) continue;
        emit(params_.other_class, cl);
      }
    }
  }
  return out;
}

}  // namespace slide
