#include "place/neighbourhood.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>

#include "geometry/pose.h"

namespace slide::place {

namespace {
std::int64_t cellOf(double v, double cell) { return static_cast<std::int64_t>(std::floor(v / cell)); }
std::uint64_t keyOf(std::int64_t cx, std::int64_t cy) {
  return (static_cast<std::uint64_t>(cx) << 32) ^ (static_cast<std::uint64_t>(cy) & 0xffffffffULL);
}
}  // namespace

Neighbourhoods::Neighbourhoods(const std::vector<Landmark>& lms, double radius, std::size_t max_neighbours)
    : radius_(std::max(radius, 1e-3)) {
  // Landmarks sorted by cell (cells of one radius): the 3 x 3 cells around one hold its neighbours.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> cells;
  cells.reserve(lms.size());
  for (std::uint32_t i = 0; i < lms.size(); ++i)
    if (lms[i].p.allFinite()) cells.emplace_back(keyOf(cellOf(lms[i].p.x(), radius_), cellOf(lms[i].p.y(), radius_)), i);
  std::sort(cells.begin(), cells.end());
  start_.assign(lms.size() + 1, 0);
  descriptors_.assign(lms.size(), NeighbourhoodDescriptor::Zero());
  const double ring = radius_ / kNeighbourhoodRings;
  std::vector<Neighbour> mine;
  for (std::size_t i = 0; i < lms.size(); ++i) {
    mine.clear();
    const Eigen::Vector3d& p = lms[i].p;
    if (p.allFinite()) {
      const std::int64_t cx = cellOf(p.x(), radius_), cy = cellOf(p.y(), radius_);
      for (std::int64_t dx = -1; dx <= 1; ++dx)
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          const std::uint64_t key = keyOf(cx + dx, cy + dy);
          auto it = std::lower_bound(cells.begin(), cells.end(), std::pair<std::uint64_t, std::uint32_t>{key, 0});
          for (; it != cells.end() && it->first == key; ++it) {
            if (it->second == i) continue;
            const Eigen::Vector2d d = (lms[it->second].p - p).head<2>();
            const double dist = d.norm();
            if (dist <= radius_)
              mine.push_back({static_cast<float>(dist), static_cast<float>(std::atan2(d.y(), d.x())), lms[it->second].class_id});
          }
        }
    }
    std::sort(mine.begin(), mine.end(), [](const Neighbour& x, const Neighbour& y) {
      return x.dist < y.dist || (x.dist == y.dist && x.angle < y.angle);
    });
    if (mine.size() > max_neighbours) mine.resize(max_neighbours);
    // Descriptor: each neighbour shared between the two nearest rings (linear in distance).
    std::complex<double> h1[kNeighbourhoodRings], h2[kNeighbourhoodRings];
    double count[kNeighbourhoodRings] = {};
    for (const Neighbour& n : mine) {
      const double r = std::clamp(n.dist / ring - 0.5, 0.0, kNeighbourhoodRings - 1.0);
      const int k0 = std::min(static_cast<int>(r), kNeighbourhoodRings - 1), k1 = std::min(k0 + 1, kNeighbourhoodRings - 1);
      const double w1 = r - k0, w0 = 1.0 - w1;
      const std::complex<double> e1 = std::polar(1.0, static_cast<double>(n.angle)), e2 = e1 * e1;
      count[k0] += w0, h1[k0] += w0 * e1, h2[k0] += w0 * e2;
      count[k1] += w1, h1[k1] += w1 * e1, h2[k1] += w1 * e2;
    }
    for (int k = 0; k < kNeighbourhoodRings; ++k) {
      descriptors_[i][3 * k] = count[k];
      descriptors_[i][3 * k + 1] = std::abs(h1[k]);
      descriptors_[i][3 * k + 2] = std::abs(h2[k]);
    }
    items_.insert(items_.end(), mine.begin(), mine.end());
    start_[i + 1] = static_cast<std::uint32_t>(items_.size());
  }
}

LocalYaw localYaw(const Neighbourhoods& na, std::size_t i, const Neighbourhoods& nb, std::size_t j, double dist_tol,
                  double min_dist, double bin) {
  constexpr int kMaxBins = 720;
  const int bins = std::clamp(static_cast<int>(std::lround(2 * M_PI / bin)), 3, kMaxBins);
  const float width = static_cast<float>(2 * M_PI / bins), pi = static_cast<float>(M_PI), two_pi = 2 * pi;
  std::array<int, kMaxBins + 2> hist;  // bin k at k + 1; the ends wrap around into 0 and bins + 1
  std::fill_n(hist.begin(), bins + 2, 0);
  // Pairs of same-class neighbours at about the same distance (both lists sorted by distance);
  // the difference of their directions wrapped to [-pi, pi).
  const float tol = static_cast<float>(dist_tol), lo_dist = static_cast<float>(min_dist);
  auto pairs = [&](auto&& visit) {
    const Neighbourhoods::Neighbour* lo = nb.begin(j);
    for (const auto* p = na.begin(i); p != na.end(i); ++p) {
      if (p->dist < lo_dist) continue;
      while (lo != nb.end(j) && lo->dist < p->dist - tol) ++lo;
      for (const auto* q = lo; q != nb.end(j) && q->dist <= p->dist + tol; ++q) {
        if (q->class_id != p->class_id || q->dist < lo_dist) continue;
        float d = p->angle - q->angle;  // both in [-pi, pi]
        d += d < -pi ? two_pi : (d >= pi ? -two_pi : 0.0f);
        visit(d);
      }
    }
  };
  LocalYaw out;
  pairs([&](float yaw) {
    ++hist[static_cast<std::size_t>(std::clamp(static_cast<int>((yaw + pi) / width), 0, bins - 1) + 1)];
    ++out.pairs;
  });
  hist[0] = hist[static_cast<std::size_t>(bins)];
  hist[static_cast<std::size_t>(bins) + 1] = hist[1];
  int best_bin = 0;
  for (int k = 0; k < bins; ++k) {
    const int v = hist[static_cast<std::size_t>(k)] + hist[static_cast<std::size_t>(k) + 1] + hist[static_cast<std::size_t>(k) + 2];
    if (v > out.votes) out.votes = v, best_bin = k;
  }
  out.window_share = 3.0 / bins;
  if (out.votes == 0) return out;
  // Circular mean of the votes in the window (offsets from its centre, which stay small).
  const double centre = -M_PI + (best_bin + 0.5) * width;
  double sum = 0;
  int n = 0;
  pairs([&](float yaw) {
    double off = yaw - centre;  // within (-2 pi, 2 pi)
    off += off < -M_PI ? 2 * M_PI : (off >= M_PI ? -2 * M_PI : 0.0);
    if (std::abs(off) <= 1.5 * width) sum += off, ++n;
  });
  out.yaw = wrapAngle(centre + (n ? sum / n : 0.0));
  return out;
}

}  // namespace slide::place
