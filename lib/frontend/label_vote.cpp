#include "frontend/label_vote.h"

#include <array>
#include <cmath>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace slide::frontend {

namespace {
// A voxel's integer coordinates packed in 21 bits each (+-1 million cells: +-200 km at 0.2 m).
std::int64_t voxelKey(int x, int y, int z) {
  constexpr std::int64_t kMask = (1 << 21) - 1;
  return ((static_cast<std::int64_t>(x) & kMask) << 42) | ((static_cast<std::int64_t>(y) & kMask) << 21) |
         (static_cast<std::int64_t>(z) & kMask);
}
}  // namespace

std::vector<uint16_t> voteLabels(const io::LabelledScan& scan, const std::function<bool(uint16_t)>& is_object,
                                 const LabelVoteParams& params) {
  std::vector<uint16_t> out = scan.semantic;
  if (!(params.radius > 0) || out.size() != scan.size()) return out;
  const double inv = 1.0 / params.radius, r2 = params.radius * params.radius,
               range2 = params.max_range * params.max_range;
  std::vector<std::array<int, 3>> cell(scan.size());
  std::vector<char> usable(scan.size(), 0);
  std::vector<int> objects;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const Eigen::Vector3f& p = scan.xyz[i];
    if (!p.allFinite() || double(p.x()) * p.x() + double(p.y()) * p.y() > range2) continue;
    usable[i] = 1;
    cell[i] = {static_cast<int>(std::floor(p.x() * inv)), static_cast<int>(std::floor(p.y() * inv)),
               static_cast<int>(std::floor(p.z() * inv))};
    if (is_object(scan.semantic[i])) objects.push_back(static_cast<int>(i));
  }
  if (objects.empty()) return out;
  // Only the voxels around object points are filled: the rest of the scan never votes.
  std::unordered_set<std::int64_t> own;  // the object points' voxels, each once
  std::vector<std::array<int, 3>> own_cells;
  for (int i : objects)
    if (own.insert(voxelKey(cell[i][0], cell[i][1], cell[i][2])).second) own_cells.push_back(cell[i]);
  std::unordered_set<std::int64_t> near;
  near.reserve(own_cells.size() * 8);
  for (const auto& c : own_cells)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) near.insert(voxelKey(c[0] + dx, c[1] + dy, c[2] + dz));
  std::unordered_map<std::int64_t, std::vector<int>> voxels;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (!usable[i]) continue;
    const std::int64_t key = voxelKey(cell[i][0], cell[i][1], cell[i][2]);
    if (near.count(key)) voxels[key].push_back(static_cast<int>(i));
  }
  std::vector<std::pair<uint16_t, int>> counts;  // label -> points within the radius
  for (int i : objects) {
    counts.clear();
    const Eigen::Vector3f& p = scan.xyz[i];
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = voxels.find(voxelKey(cell[i][0] + dx, cell[i][1] + dy, cell[i][2] + dz));
          if (it == voxels.end()) continue;
          for (int j : it->second) {
            if ((scan.xyz[j] - p).squaredNorm() > r2) continue;
            const uint16_t l = scan.semantic[j];
            auto c = counts.begin();
            while (c != counts.end() && c->first != l) ++c;
            if (c == counts.end()) counts.emplace_back(l, 1);
            else ++c->second;
          }
        }
    const uint16_t own = scan.semantic[i];
    int own_n = 0, best_n = 0;
    uint16_t best = own;
    for (const auto& [l, n] : counts) {
      if (l == own) own_n = n;
      if (n > best_n) best = l, best_n = n;
    }
    if (best_n > own_n) out[i] = best;
  }
  return out;
}

}  // namespace slide::frontend
