#include "frontend/free_space.h"

#include <algorithm>
#include <cmath>

#include "frontend/azimuth.h"

namespace slide::frontend {

FreeSpace::FreeSpace(const Cloud& cloud, FreeSpaceParams params) : cloud_(cloud), p_(params) {
  if (p_.cell <= 0) return;
  bins_ = std::max(1, static_cast<int>(std::lround(360.0 / std::max(0.05, p_.azimuth_step_deg))));
  start_.assign(bins_ + 1, 0);
  std::vector<int> bin_of(cloud.size(), -1);
  const double scale = bins_ / (2 * M_PI);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& q = cloud[i];
    if (!q.allFinite() || q.head<2>().squaredNorm() < 1e-6f) continue;
    bin_of[i] = std::clamp(static_cast<int>((azimuthOf(q.y(), q.x()) + M_PI) * scale), 0, bins_ - 1);
    ++start_[bin_of[i] + 1];
  }
  for (int b = 0; b < bins_; ++b) start_[b + 1] += start_[b];
  range_.resize(start_[bins_]);
  slope_.resize(start_[bins_]);
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (bin_of[i] < 0) continue;
    const int k = fill[bin_of[i]]++;
    range_[k] = cloud[i].head<2>().norm();
    slope_[k] = cloud[i].z() / range_[k];
  }
}

Cloud FreeSpace::near(const std::vector<int>& cluster, float ground_z, double reach) const {
  Cloud out;
  if (p_.cell <= 0 || cluster.empty() || reach <= 0) return out;
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (int i : cluster) c += cloud_[i].head<2>().cast<double>();
  c /= static_cast<double>(cluster.size());
  double radius = 0;
  for (int i : cluster) radius = std::max(radius, (cloud_[i].head<2>().cast<double>() - c).norm());
  radius += reach;
  const double dist = c.norm();
  const double s_lo = std::max(0.0, dist - radius), s_hi = dist + radius;
  // Azimuth bins whose lines of sight can pass within `radius` of c.
  int b0 = 0, b1 = bins_ - 1;
  if (dist > radius) {
    const double half = std::asin(radius / dist), mid = std::atan2(c.y(), c.x()) + M_PI;
    const double scale = bins_ / (2 * M_PI);
    b0 = static_cast<int>(std::floor((mid - half) * scale));
    b1 = static_cast<int>(std::floor((mid + half) * scale));
  }
  const double z_lo = ground_z + p_.band_low, z_hi = ground_z + p_.band_high, step = 0.5 * p_.cell;
  const double inv = 1.0 / p_.cell, r2 = radius * radius;
  // The cells of the square around c, on the grid of side p_.cell through the origin.
  const int gx0 = static_cast<int>(std::floor((c.x() - radius) * inv)), gy0 = static_cast<int>(std::floor((c.y() - radius) * inv));
  const int side = static_cast<int>(std::ceil(2 * radius * inv)) + 2;
  std::vector<char> cells(static_cast<std::size_t>(side) * side, 0);
  std::vector<std::pair<double, double>> spans;  // ranges s over which a line of sight of the bin crosses the band
  const double bin_width = 2 * M_PI / bins_;
  for (int bb = b0; bb <= b1; ++bb) {
    const int b = ((bb % bins_) + bins_) % bins_;
    spans.clear();
    for (int k = start_[b]; k < start_[b + 1]; ++k) {
      const double R = range_[k], end = std::min(s_hi, R - p_.margin);
      if (end <= s_lo) continue;
      // The line of sight lies at z = slope * s.
      const double slope = slope_[k];
      double a = s_lo, e = end;
      if (std::abs(slope) < 1e-9) {
        if (z_lo > 0 || z_hi < 0) continue;
      } else {
        const double s1 = z_lo / slope, s2 = z_hi / slope;
        a = std::max(a, std::min(s1, s2));
        e = std::min(e, std::max(s1, s2));
      }
      if (e > a) spans.emplace_back(a, e);
    }
    if (spans.empty()) continue;
    // The bin's lines of sight are marched together along its middle azimuth, over the union of
    // their spans.
    std::sort(spans.begin(), spans.end());
    const double az = (b + 0.5) * bin_width - M_PI;
    const Eigen::Vector2d dir(std::cos(az), std::sin(az));
    double s = spans.front().first, reach_end = spans.front().second;
    for (std::size_t i = 0; i <= spans.size(); ++i) {
      if (i < spans.size() && spans[i].first <= reach_end) {
        reach_end = std::max(reach_end, spans[i].second);
        continue;
      }
      for (; s <= reach_end; s += step) {
        const Eigen::Vector2d x = s * dir;
        if ((x - c).squaredNorm() > r2) continue;
        const int ix = static_cast<int>(std::floor(x.x() * inv)) - gx0, iy = static_cast<int>(std::floor(x.y() * inv)) - gy0;
        if (ix >= 0 && iy >= 0 && ix < side && iy < side) cells[static_cast<std::size_t>(iy) * side + ix] = 1;
      }
      if (i < spans.size()) s = spans[i].first, reach_end = spans[i].second;
    }
  }
  const float z = static_cast<float>(0.5 * (z_lo + z_hi));
  for (int iy = 0; iy < side; ++iy)
    for (int ix = 0; ix < side; ++ix)
      if (cells[static_cast<std::size_t>(iy) * side + ix])
        out.emplace_back(static_cast<float>((gx0 + ix + 0.5) * p_.cell), static_cast<float>((gy0 + iy + 0.5) * p_.cell), z);
  return out;
}

}  // namespace slide::frontend
