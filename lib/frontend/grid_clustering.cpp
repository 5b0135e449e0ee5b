#include "frontend/grid_clustering.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>

namespace slide::frontend {

namespace {
constexpr std::int64_t kLimit = 1 << 20;  // cell coordinates beyond +-2^20 are dropped
constexpr std::size_t kRadixMin = 256;    // fewer points are sorted by comparison

int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

int bitsFor(std::uint64_t n) {  // bits that hold 0..n
  int b = 0;
  while (b < 64 && (n >> b) != 0) ++b;
  return b;
}

// Least-significant-digit radix sort of keys below 2^bits, a byte per pass (passes whose byte
// is the same in every key are skipped); linear where std::sort is n log n.
void radixSort(std::vector<std::uint64_t>& keys, int bits) {
  const int passes = (bits + 7) / 8;
  std::vector<std::array<std::size_t, 256>> count(passes);
  for (auto& c : count) c.fill(0);
  for (std::uint64_t k : keys)
    for (int d = 0; d < passes; ++d) ++count[d][(k >> (8 * d)) & 0xff];
  std::vector<std::uint64_t> tmp(keys.size());
  for (int d = 0; d < passes; ++d) {
    auto& c = count[d];
    if (std::find(c.begin(), c.end(), keys.size()) != c.end()) continue;
    std::size_t sum = 0;
    for (auto& n : c) sum += std::exchange(n, sum);
    for (std::uint64_t k : keys) tmp[c[(k >> (8 * d)) & 0xff]++] = k;
    keys.swap(tmp);
  }
}
}  // namespace

std::vector<std::vector<int>> clusterGrid(const Cloud& cloud, const std::vector<int>& subset,
                                          const GridClusterParams& params) {
  std::vector<int> all;
  if (subset.empty()) {
    all.resize(cloud.size());
    std::iota(all.begin(), all.end(), 0);
  }
  const std::vector<int>& idx = subset.empty() ? all : subset;
  const double inv = 1.0 / params.cell;
  // Cell coordinates and their bounding box.
  std::vector<std::array<std::int64_t, 3>> coord;
  std::vector<int> point;
  coord.reserve(idx.size());
  point.reserve(idx.size());
  std::array<std::int64_t, 3> lo{kLimit, kLimit, kLimit}, hi{-kLimit, -kLimit, -kLimit};
  for (int i : idx) {
    const auto& p = cloud[i];
    if (!p.allFinite()) continue;
    const std::array<std::int64_t, 3> c{static_cast<std::int64_t>(std::floor(p.x() * inv)),
                                        static_cast<std::int64_t>(std::floor(p.y() * inv)),
                                        params.planar ? 0 : static_cast<std::int64_t>(std::floor(p.z() * inv))};
    if (std::abs(c[0]) >= kLimit || std::abs(c[1]) >= kLimit || std::abs(c[2]) >= kLimit) continue;
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
    coord.push_back(c);
    point.push_back(i);
  }
  if (point.empty()) return {};
  // Keys pack the cell coordinates, shifted by one past the box so every neighbour is in range,
  // in x, y, z order: a cell's neighbour is its key plus a fixed offset, and key order is
  // lexicographic. Sorting (key, point) puts each cell's points together in index order; when
  // both fit one 64-bit word (always, short of millions of points or kilometres of cells) the
  // words are radix sorted.
  std::array<int, 3> bits;
  for (int a = 0; a < 3; ++a) bits[a] = bitsFor(static_cast<std::uint64_t>(hi[a] - lo[a] + 2));
  auto key = [&](const std::array<std::int64_t, 3>& c) {
    return (static_cast<std::uint64_t>(c[0] - lo[0] + 1) << (bits[1] + bits[2])) |
           (static_cast<std::uint64_t>(c[1] - lo[1] + 1) << bits[2]) | static_cast<std::uint64_t>(c[2] - lo[2] + 1);
  };
  const int point_bits = bitsFor(cloud.size());
  std::vector<std::uint64_t> cell_of(point.size());  // sorted: the cell of each entry of `order`
  std::vector<int> order(point.size());
  if (bits[0] + bits[1] + bits[2] + point_bits <= 64) {
    std::vector<std::uint64_t> packed(point.size());
    for (std::size_t k = 0; k < point.size(); ++k)
      packed[k] = key(coord[k]) << point_bits | static_cast<std::uint64_t>(point[k]);
    if (packed.size() < kRadixMin)  // a radix pass walks 256 counters whatever the size
      std::sort(packed.begin(), packed.end());
    else
      radixSort(packed, bits[0] + bits[1] + bits[2] + point_bits);
    const std::uint64_t mask = (std::uint64_t{1} << point_bits) - 1;
    for (std::size_t k = 0; k < packed.size(); ++k)
      cell_of[k] = packed[k] >> point_bits, order[k] = static_cast<int>(packed[k] & mask);
  } else {
    std::vector<std::pair<std::uint64_t, int>> keyed(point.size());
    for (std::size_t k = 0; k < point.size(); ++k) keyed[k] = {key(coord[k]), point[k]};
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t k = 0; k < keyed.size(); ++k) cell_of[k] = keyed[k].first, order[k] = keyed[k].second;
  }
  // Occupied cells: keys and the range of `order` each covers.
  std::vector<std::uint64_t> cells;
  std::vector<std::size_t> start;
  for (std::size_t k = 0; k < cell_of.size(); ++k) {
    if (k == 0 || cell_of[k] != cell_of[k - 1]) {
      cells.push_back(cell_of[k]);
      start.push_back(k);
    }
  }
  start.push_back(cell_of.size());
  std::vector<int> parent(cells.size());
  std::iota(parent.begin(), parent.end(), 0);
  // Half of the neighbourhood (lexicographically larger offsets) suffices for union-find.
  std::vector<std::uint64_t> offsets;
  const int dz_max = params.planar ? 0 : 1;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -dz_max; dz <= dz_max; ++dz) {
        const std::int64_t off = dx * (std::int64_t{1} << (bits[1] + bits[2])) + dy * (std::int64_t{1} << bits[2]) + dz;
        if (off > 0) offsets.push_back(static_cast<std::uint64_t>(off));
      }
  // Neighbour keys cells[c] + off grow with c, so one forward-moving cursor per offset finds
  // them all in linear time (no search per cell).
  std::vector<std::size_t> cursor(offsets.size(), 0);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    for (std::size_t k = 0; k < offsets.size(); ++k) {
      const std::uint64_t target = cells[c] + offsets[k];
      std::size_t& p = cursor[k];
      while (p < cells.size() && cells[p] < target) ++p;
      if (p < cells.size() && cells[p] == target) {
        const int a = findRoot(parent, static_cast<int>(c)), b = findRoot(parent, static_cast<int>(p));
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
      }
    }
  }
  // Clusters numbered in the order of their first cell, each sized before it is filled.
  std::vector<int> label(cells.size(), -1), cluster_of(cells.size());
  std::vector<std::size_t> size;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const int r = findRoot(parent, static_cast<int>(c));
    if (label[r] < 0) {
      label[r] = static_cast<int>(size.size());
      size.push_back(0);
    }
    cluster_of[c] = label[r];
    size[label[r]] += start[c + 1] - start[c];
  }
  std::vector<std::vector<int>> clusters(size.size());
  for (std::size_t l = 0; l < size.size(); ++l) clusters[l].reserve(size[l]);
  for (std::size_t c = 0; c < cells.size(); ++c)
    clusters[cluster_of[c]].insert(clusters[cluster_of[c]].end(), order.begin() + start[c], order.begin() + start[c + 1]);
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

}  // namespace slide::frontend
