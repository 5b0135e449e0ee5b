#include "frontend/stacked_split.h"

#include <algorithm>
#include <cmath>

namespace slide::frontend {

namespace {
struct Arc {
  double height, width;  // mean height above ground; width across the line of sight (metres)
};

// One arc per beam through the cluster (of at least min_arc_points returns), lowest first.
std::vector<Arc> arcsOf(const Cloud& cloud, const std::vector<float>& h, const std::vector<int>& cluster,
                        const StackedSplitParams& p) {
  // Azimuths are taken about the cluster's mean bearing (no wrap at +-pi).
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (int i : cluster) mean += cloud[i].head<2>().cast<double>().normalized();
  if (mean.norm() < 1e-9) return {};
  const double bearing = std::atan2(mean.y(), mean.x());
  struct Return {
    double elevation, azimuth, range;
    int index;
  };
  std::vector<Return> returns;
  returns.reserve(cluster.size());
  for (int i : cluster) {
    const double r = cloud[i].head<2>().norm();
    if (!(r > 0)) continue;
    const double azimuth = std::atan2(double(cloud[i].y()), double(cloud[i].x()));
    returns.push_back({std::atan2(double(cloud[i].z()), r), std::remainder(azimuth - bearing, 2 * M_PI), r, i});
  }
  std::sort(returns.begin(), returns.end(), [](const Return& a, const Return& b) { return a.elevation < b.elevation; });
  std::vector<Arc> arcs;
  const double tolerance = p.beam_tolerance_deg * M_PI / 180;
  for (std::size_t a = 0; a < returns.size();) {
    std::size_t b = a;
    double lo = returns[a].azimuth, hi = lo, range = 0, height = 0;
    for (; b < returns.size() && returns[b].elevation - returns[a].elevation <= tolerance; ++b) {
      lo = std::min(lo, returns[b].azimuth), hi = std::max(hi, returns[b].azimuth);
      range += returns[b].range, height += h[returns[b].index];
    }
    const double n = static_cast<double>(b - a);
    if (b - a >= static_cast<std::size_t>(p.min_arc_points)) arcs.push_back({height / n, (hi - lo) * range / n});
    a = b;
  }
  std::sort(arcs.begin(), arcs.end(), [](const Arc& a, const Arc& b) { return a.height < b.height; });
  return arcs;
}
}  // namespace

std::optional<std::pair<std::vector<int>, std::vector<int>>> splitAtNeck(const Cloud& cloud, const std::vector<float>& h,
                                                                         const std::vector<int>& cluster,
                                                                         const StackedSplitParams& p) {
  if (p.max_neck_ratio <= 0 || cluster.size() < 2 * static_cast<std::size_t>(p.min_points)) return std::nullopt;
  const std::vector<Arc> arcs = arcsOf(cloud, h, cluster, p);
  const std::size_t n = arcs.size();
  if (n < 3) return std::nullopt;
  // The widest arc below and above each one.
  std::vector<double> below(n, 0.0), above(n, 0.0);
  for (std::size_t k = 1; k < n; ++k) below[k] = std::max(below[k - 1], arcs[k - 1].width);
  for (std::size_t k = n - 1; k-- > 0;) above[k] = std::max(above[k + 1], arcs[k + 1].width);
  std::vector<std::pair<double, double>> necks;  // ratio, height
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double narrower = std::min(below[k], above[k]), w = arcs[k].width;
    if (arcs[k].height < p.min_neck_height || w > p.max_neck_ratio * narrower || narrower - w < p.min_neck_depth)
      continue;
    if (arcs[k - 1].width > p.max_side_ratio * below[k] || arcs[k + 1].width > p.max_side_ratio * above[k]) continue;
    necks.emplace_back(w / narrower, arcs[k].height);
  }
  // Narrowest first; the first whose parts are both big enough splits the cluster.
  std::sort(necks.begin(), necks.end());
  for (const auto& neck : necks) {
    std::pair<std::vector<int>, std::vector<int>> parts;
    float lo_min = INFINITY, lo_max = -INFINITY, up_min = INFINITY, up_max = -INFINITY;
    for (int i : cluster) {
      if (h[i] < neck.second) parts.first.push_back(i), lo_min = std::min(lo_min, h[i]), lo_max = std::max(lo_max, h[i]);
      else parts.second.push_back(i), up_min = std::min(up_min, h[i]), up_max = std::max(up_max, h[i]);
    }
    const auto big = [&](const std::vector<int>& part, float low, float high) {
      return static_cast<int>(part.size()) >= p.min_points && high - low >= p.min_height;
    };
    if (big(parts.first, lo_min, lo_max) && big(parts.second, up_min, up_max)) return parts;
  }
  return std::nullopt;
}

}  // namespace slide::frontend
