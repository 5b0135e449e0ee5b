#include "place/class_grid.h"

#include <algorithm>
#include <cmath>

namespace slide::place {

ClassGrid::ClassGrid(const std::vector<Landmark>& lms, double cell) : lms_(lms), cell_(cell), x0_(0), y0_(0) {
  if (lms.empty()) return;
  double x1 = -1e300, y1 = -1e300;
  x0_ = y0_ = 1e300;
  for (const Landmark& l : lms) {
    x0_ = std::min(x0_, l.p.x());
    y0_ = std::min(y0_, l.p.y());
    x1 = std::max(x1, l.p.x());
    y1 = std::max(y1, l.p.y());
  }
  // Cells grow when the extent would need more than kMaxCells (stray far objects): queries
  // stay exact, only slower, and memory stays bounded.
  constexpr double kMaxCells = 4e6;
  cell_ = std::max(cell_, std::sqrt((x1 - x0_) * (y1 - y0_) / kMaxCells) * 1.01);
  cell_ = std::max({cell_, (x1 - x0_) / kMaxCells, (y1 - y0_) / kMaxCells});
  nx_ = static_cast<long>((x1 - x0_) / cell_) + 1;
  ny_ = static_cast<long>((y1 - y0_) / cell_) + 1;
  std::map<int, std::vector<std::pair<long, std::uint32_t>>> cells;
  for (std::uint32_t i = 0; i < lms.size(); ++i) {
    const long cx = static_cast<long>((lms[i].p.x() - x0_) / cell_), cy = static_cast<long>((lms[i].p.y() - y0_) / cell_);
    cells[lms[i].class_id].emplace_back(cy * nx_ + cx, i);
  }
  for (auto& [cls, list] : cells) {
    std::sort(list.begin(), list.end());
    Buckets& b = classes_[cls];
    b.start.assign(nx_ * ny_ + 1, 0);
    for (const auto& [c, i] : list) ++b.start[c + 1];
    for (std::size_t c = 1; c < b.start.size(); ++c) b.start[c] += b.start[c - 1];
    for (const auto& [c, i] : list) b.items.push_back(i);
  }
}

long ClassGrid::nearestWithin(int class_id, double x, double y, double r, const Eigen::Vector3d& size,
                              double size_tol) const {
  const auto it = classes_.find(class_id);
  if (it == classes_.end()) return -1;
  const Buckets& b = it->second;
  const long cx0 = std::max(0L, static_cast<long>(std::floor((x - r - x0_) / cell_)));
  const long cx1 = std::min(nx_ - 1, static_cast<long>(std::floor((x + r - x0_) / cell_)));
  const long cy0 = std::max(0L, static_cast<long>(std::floor((y - r - y0_) / cell_)));
  const long cy1 = std::min(ny_ - 1, static_cast<long>(std::floor((y + r - y0_) / cell_)));
  long best = -1;
  double best_d2 = r * r;
  for (long cy = cy0; cy <= cy1; ++cy)
    for (long cx = cx0; cx <= cx1; ++cx) {
      const long c = cy * nx_ + cx;
      for (std::uint32_t k = b.start[c]; k < b.start[c + 1]; ++k) {
        const Landmark& l = lms_[b.items[k]];
        const double dx = l.p.x() - x, dy = l.p.y() - y, d2 = dx * dx + dy * dy;
        if (d2 <= best_d2 && sizesAgree(l.size, size, size_tol)) {
          best_d2 = d2;
          best = b.items[k];
        }
      }
    }
  return best;
}

}  // namespace slide::place
