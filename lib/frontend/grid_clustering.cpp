#include "frontend/grid_clustering.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace slide {

namespace {
constexpr std::int64_t kBias = 1 << 20;  // cell coordinates in [-2^20, 2^20)

std::int64_t packKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  return ((x + kBias) << 42) | ((y + kBias) << 21) | (z + kBias);
}

int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}
}  // namespace

std::vector<std::vector<int>> clusterGrid(const Cloud& cloud, const std::vector<int>& subset,
                                          const GridClusterParams& params) {
  std::vector<int> idx = subset;
  if (idx.empty()) {
    idx.resize(cloud.size());
    std::iota(idx.begin(), idx.end(), 0);
  }
  const double inv = 1.0 / params.cell;
  std::vector<std::pair<std::int64_t, int>> keyed;
  keyed.reserve(idx.size());
  for (int i : idx) {
    const auto& p = cloud[i];
    if (!p.allFinite()) continue;
    const std::int64_t x = static_cast<std::int64_t>(std::floor(p.x() * inv));
    const std::int64_t y = static_cast<std::int64_t>(std::floor(p.y() * inv));
    const std::int64_t z = params.planar ? 0 : static_cast<std::int64_t>(std::floor(p.z() * inv));
    if (std::abs(x) >= kBias || std::abs(y) >= kBias || std::abs(z) >= kBias) continue;
    keyed.emplace_back(packKey(x, y, z), i);
  }
  std::sort(keyed.begin(), keyed.end());
  // Occupied cells: keys and the range of `keyed` each covers.
  std::vector<std::int64_t> cells;
  std::vector<std::size_t> start;
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    if (i == 0 || keyed[i].first != keyed[i - 1].first) {
      cells.push_back(keyed[i].first);
      start.push_back(i);
    }
  }
  start.push_back(keyed.size());
  std::vector<int> parent(cells.size());
  std::iota(parent.begin(), parent.end(), 0);
  // Half of the neighbourhood (lexicographically larger offsets) suffices for union-find.
  std::vector<std::int64_t> offsets;
  const int dz_max = params.planar ? 0 : 1;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -dz_max; dz <= dz_max; ++dz) {
        const std::int64_t off = (static_cast<std::int64_t>(dx) << 42) + (static_cast<std::int64_t>(dy) << 21) + dz;
        if (off > 0) offsets.push_back(off);
      }
  // Neighbour keys cells[c] + off grow with c, so one forward-moving cursor per offset finds
  // them all in linear time (no search per cell).
  std::vector<std::size_t> cursor(offsets.size(), 0);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    for (std::size_t k = 0; k < offsets.size(); ++k) {
      const std::int64_t key = cells[c] + offsets[k];
      std::size_t& p = cursor[k];
      while (p < cells.size() && cells[p] < key) ++p;
      if (p < cells.size() && cells[p] == key) {
        const int a = findRoot(parent, static_cast<int>(c)), b = findRoot(parent, static_cast<int>(p));
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
      }
    }
  }
  std::vector<int> label(cells.size(), -1);
  std::vector<std::vector<int>> clusters;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const int r = findRoot(parent, static_cast<int>(c));
    if (label[r] < 0) {
      label[r] = static_cast<int>(clusters.size());
      clusters.emplace_back();
    }
    auto& cl = clusters[label[r]];
    for (std::size_t k = start[c]; k < start[c + 1]; ++k) cl.push_back(keyed[k].second);
  }
  clusters.erase(std::remove_if(clusters.begin(), clusters.end(),
                                [&](const std::vector<int>& cl) {
                                  return static_cast<int>(cl.size()) < params.min_points ||
                                         static_cast<int>(cl.size()) > params.max_points;
                                }),
                 clusters.end());
  std::sort(clusters.begin(), clusters.end(),
            [](const std::vector<int>& a, const std::vector<int>& b) { return a.size() > b.size(); });
  return clusters;
}

}  // namespace slide
