#include "place/delaunay.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <opencv2/imgproc.hpp>
#include <unordered_map>

namespace slide::place {

namespace {
std::uint64_t cellKey(double x, double y, double cell) {
  const auto qx = static_cast<std::int64_t>(std::floor(x / cell));
  const auto qy = static_cast<std::int64_t>(std::floor(y / cell));
  return (static_cast<std::uint64_t>(qx) * 0x9E3779B97F4A7C15ULL) ^ static_cast<std::uint64_t>(qy);
}

// Position of cell (x, y) of a 2^16 x 2^16 grid along the Hilbert curve.
std::uint64_t hilbertIndex(std::uint32_t x, std::uint32_t y) {
  constexpr std::uint32_t n = 1u << 16;
  std::uint64_t d = 0;
  for (std::uint32_t s = n / 2; s > 0; s /= 2) {
    const std::uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += static_cast<std::uint64_t>(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) {  // rotate the quadrant
      if (rx == 1) {
        x = n - 1 - x;
        y = n - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

std::uint64_t floatKey(float x, float y) {
  std::uint32_t bx, by;
  std::memcpy(&bx, &x, 4);
  std::memcpy(&by, &y, 4);
  return (static_cast<std::uint64_t>(bx) << 32) | by;
}
}  // namespace

std::vector<Triangle> delaunay2d(const std::vector<Eigen::Vector2d>& pts, const std::function<bool()>& out_of_time) {
  std::vector<Triangle> out;
  // Centre the points so that float coordinates keep millimetre precision.
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  std::vector<std::uint32_t> kept;
  for (std::uint32_t i = 0; i < pts.size(); ++i)
    if (pts[i].allFinite()) {
      centre += pts[i];
      kept.push_back(i);
    }
  if (kept.size() < 3) return out;
  centre /= static_cast<double>(kept.size());

  // Merge near duplicates (1 mm grid, checking neighbouring cells).
  const double cell = 1e-3;
  std::unordered_map<std::uint64_t, std::uint32_t> seen;
  std::vector<std::uint32_t> unique;
  double lo_x = 1e300, lo_y = 1e300, hi_x = -1e300, hi_y = -1e300;
  for (std::uint32_t i : kept) {
    const Eigen::Vector2d p = pts[i] - centre;
    bool dup = false;
    for (int dx = -1; dx <= 1 && !dup; ++dx)
      for (int dy = -1; dy <= 1 && !dup; ++dy) {
        const auto it = seen.find(cellKey(p.x() + dx * cell, p.y() + dy * cell, cell));
        dup = it != seen.end() && (pts[it->second] - pts[i]).norm() < cell;
      }
    if (dup) continue;
    seen.emplace(cellKey(p.x(), p.y(), cell), i);
    unique.push_back(i);
    lo_x = std::min(lo_x, p.x());
    lo_y = std::min(lo_y, p.y());
    hi_x = std::max(hi_x, p.x());
    hi_y = std::max(hi_y, p.y());
  }
  if (unique.size() < 3) return out;
  // Subdiv2D takes an int rectangle and float points: an extent beyond 1e7 m (float keeps
  // metres there, int keeps the rectangle) is no map of ours; callers drop such objects first.
  if (!(hi_x - lo_x < 1e7 && hi_y - lo_y < 1e7)) return out;

  // Insertion along a Hilbert curve: Subdiv2D locates each new point by walking from the edge it
  // touched last, so neighbours in insertion order keep the walks short (a map in random order
  // makes every walk cross the map: N^1.5 in all). The triangulation is the same.
  {
    const double span = std::max({hi_x - lo_x, hi_y - lo_y, 1e-9});
    std::vector<std::pair<std::uint64_t, std::uint32_t>> order;
    order.reserve(unique.size());
    for (std::uint32_t i : unique) {
      const Eigen::Vector2d p = pts[i] - centre;
      const auto q = [&](double v, double lo) { return static_cast<std::uint32_t>(std::min(65535.0, (v - lo) / span * 65535.0)); };
      order.emplace_back(hilbertIndex(q(p.x(), lo_x), q(p.y(), lo_y)), i);
    }
    std::sort(order.begin(), order.end());
    for (std::size_t k = 0; k < order.size(); ++k) unique[k] = order[k].second;
  }
  const double margin = 1.0 + 0.01 * std::max(hi_x - lo_x, hi_y - lo_y);
  cv::Subdiv2D subdiv(cv::Rect(static_cast<int>(std::floor(lo_x - margin)), static_cast<int>(std::floor(lo_y - margin)),
                               static_cast<int>(std::ceil(hi_x - lo_x + 2 * margin)) + 1,
                               static_cast<int>(std::ceil(hi_y - lo_y + 2 * margin)) + 1));
  std::unordered_map<std::uint64_t, std::uint32_t> index_of;
  std::size_t inserted = 0;
  for (std::uint32_t i : unique) {
    if (out_of_time && ++inserted % 256 == 0 && out_of_time()) return out;
    const Eigen::Vector2d p = pts[i] - centre;
    const cv::Point2f q(static_cast<float>(p.x()), static_cast<float>(p.y()));
    if (index_of.emplace(floatKey(q.x, q.y), i).second) subdiv.insert(q);
  }
  std::vector<cv::Vec6f> tris;
  subdiv.getTriangleList(tris);
  out.reserve(tris.size());
  for (const cv::Vec6f& t : tris) {
    Triangle tri;
    bool ok = true;
    for (int k = 0; k < 3 && ok; ++k) {
      const auto it = index_of.find(floatKey(t[2 * k], t[2 * k + 1]));
      ok = it != index_of.end();
      if (ok) tri[k] = it->second;
    }
    if (!ok) continue;  // touches Subdiv2D's outer virtual vertices
    const Eigen::Vector2d e1 = pts[tri[1]] - pts[tri[0]], e2 = pts[tri[2]] - pts[tri[0]];
    const double area2 = std::abs(e1.x() * e2.y() - e1.y() * e2.x());
    if (area2 <= 1e-6 * std::max(e1.squaredNorm(), e2.squaredNorm())) continue;  // sliver
    out.push_back(tri);
  }
  return out;
}

}  // namespace slide::place
