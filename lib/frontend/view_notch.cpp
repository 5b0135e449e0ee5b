#include "frontend/view_notch.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "frontend/azimuth.h"
#include "frontend/point_stats.h"

namespace slide::frontend {

std::optional<std::pair<std::vector<int>, std::vector<int>>> splitAtNotch(const Cloud& cloud, const std::vector<int>& idx,
                                                                          const NotchSplitParams& p) {
  if (p.depth <= 0 || idx.size() < 4) return std::nullopt;
  // Azimuths about the cluster's mean bearing (no wrap at +-pi inside a cluster).
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  std::vector<double> zs;
  zs.reserve(idx.size());
  for (int i : idx) mean += cloud[i].head<2>().cast<double>(), zs.push_back(cloud[i].z());
  if (mean.norm() < 1e-6) return std::nullopt;
  const Eigen::Vector2f u = mean.normalized().cast<float>();  // the mean bearing
  const double bottom = quantileInPlace(zs, 0.05);
  std::vector<double> az(idx.size());
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  for (std::size_t k = 0; k < idx.size(); ++k) {
    const Eigen::Vector3f& q = cloud[idx[k]];
    az[k] = azimuthOf(u.x() * q.y() - u.y() * q.x(), u.x() * q.x() + u.y() * q.y());  // from the mean bearing
    lo = std::min(lo, az[k]), hi = std::max(hi, az[k]);
  }
  const double bin = p.bin_deg * M_PI / 180.0;
  const int n = static_cast<int>((hi - lo) / bin) + 1;
  if (n < 3) return std::nullopt;
  // Nearest horizontal range per bin over the body band; infinity where no ray hit the band.
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> near(n, inf);
  auto binOf = [&](double a) { return std::clamp(static_cast<int>((a - lo) / bin), 0, n - 1); };
  for (std::size_t k = 0; k < idx.size(); ++k) {
    const Eigen::Vector3f& q = cloud[idx[k]];
    if (q.z() < bottom + p.band_low || q.z() > bottom + p.band_high) continue;
    double& r = near[binOf(az[k])];
    r = std::min(r, double(q.head<2>().norm()));
  }
  int first = 0, last = n - 1;
  while (first < n && near[first] == inf) ++first;
  while (last > first && near[last] == inf) --last;
  if (last - first < 2) return std::nullopt;
  // How far each interior bin lies beyond the nearest return on its left and on its right.
  std::vector<double> left(n, inf), right(n, inf);
  for (int b = first + 1; b <= last; ++b) left[b] = std::min(left[b - 1], near[b - 1]);
  for (int b = last - 1; b >= first; --b) right[b] = std::min(right[b + 1], near[b + 1]);
  auto beyond = [&](int b) { return near[b] - std::max(left[b], right[b]); };
  // The deepest run of notch bins; an empty bin (rays through a gap) counts when the run
  // spans two bins or holds a return (one empty bin may be a dropped return).
  int best_mid = -1;
  double best_depth = 0;
  for (int b = first + 1; b < last;) {
    if (!(beyond(b) > p.depth)) {
      ++b;
      continue;
    }
    int e = b;
    double deepest = 0;
    bool hit = false;
    while (e < last && beyond(e) > p.depth) deepest = std::max(deepest, std::min(beyond(e), 1e3)), hit |= near[e] < inf, ++e;
    const bool real = hit || e - b >= 2;
    const double side_left = (b - first) * bin * left[b], side_right = (last - e + 1) * bin * right[e - 1];
    if (real && side_left >= p.min_side && side_right >= p.min_side && deepest > best_depth)
      best_depth = deepest, best_mid = (b + e) / 2;
    b = e;
  }
  if (best_mid < 0) return std::nullopt;
  const double cut = lo + (best_mid + 0.5) * bin;
  std::pair<std::vector<int>, std::vector<int>> parts;
  for (std::size_t k = 0; k < idx.size(); ++k) (az[k] < cut ? parts.first : parts.second).push_back(idx[k]);
  if (parts.first.empty() || parts.second.empty()) return std::nullopt;
  return parts;
}

}  // namespace slide::frontend
