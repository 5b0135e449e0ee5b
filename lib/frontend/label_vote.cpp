#include "frontend/label_vote.h"

#include <array>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "frontend/cell_key.h"

namespace slide::frontend {

namespace {
using Histogram = std::vector<std::pair<uint16_t, int>>;  // label -> points, a handful of labels

void add(Histogram& h, uint16_t label, int n) {
  for (auto& [l, c] : h)
    if (l == label) {
      c += n;
      return;
    }
  h.emplace_back(label, n);
}
}  // namespace

std::vector<uint16_t> voteLabels(const io::LabelledScan& scan, const std::function<bool(uint16_t)>& is_object,
                                 const LabelVoteParams& params) {
  std::vector<uint16_t> out = scan.semantic;
  if (!(params.cell > 0) || out.size() != scan.size()) return out;
  const double inv = 1.0 / params.cell, range2 = params.max_range * params.max_range;
  std::vector<std::array<int, 3>> cell(scan.size());
  std::vector<char> usable(scan.size(), 0);
  std::vector<int> objects;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const Eigen::Vector3f& p = scan.xyz[i];
    if (!p.allFinite() || double(p.x()) * p.x() + double(p.y()) * p.y() > range2) continue;
    const auto c = cellOf(p, inv);
    if (!c) continue;  // a return kilometres up
    usable[i] = 1;
    cell[i] = *c;
    if (is_object(scan.semantic[i])) objects.push_back(static_cast<int>(i));
  }
  if (objects.empty()) return out;
  // Only the cells around object points are counted: the rest of the scan never votes.
  std::unordered_map<std::int64_t, Histogram> block;  // an object point's cell -> the labels of its 3 x 3 x 3 block
  std::vector<std::array<int, 3>> object_cells;
  for (int i : objects)
    if (block.try_emplace(cellKey(cell[i][0], cell[i][1], cell[i][2])).second) object_cells.push_back(cell[i]);
  std::unordered_map<std::int64_t, Histogram> counts;  // every cell of those blocks -> its own labels
  counts.reserve(object_cells.size() * 8);
  for (const auto& c : object_cells)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) counts.try_emplace(cellKey(c[0] + dx, c[1] + dy, c[2] + dz));
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (!usable[i]) continue;
    const auto it = counts.find(cellKey(cell[i][0], cell[i][1], cell[i][2]));
    if (it != counts.end()) add(it->second, scan.semantic[i], 1);
  }
  for (const auto& c : object_cells) {
    Histogram& h = block[cellKey(c[0], c[1], c[2])];
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          for (const auto& [l, n] : counts[cellKey(c[0] + dx, c[1] + dy, c[2] + dz)]) add(h, l, n);
  }
  for (int i : objects) {
    const Histogram& h = block[cellKey(cell[i][0], cell[i][1], cell[i][2])];
    const uint16_t own = scan.semantic[i];
    int own_n = 0, best_n = 0;
    uint16_t best = own;
    for (const auto& [l, n] : h) {
      if (l == own) own_n = n;
      if (n > best_n) best = l, best_n = n;
    }
    if (best_n > own_n) out[i] = best;
  }
  return out;
}

}  // namespace slide::frontend
