#pragma once
// A uniform 2-D grid (x, y) of landmark indices for association look-ups; positions move
// after solves, so entries are re-bucketed with move().
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace slide::backend {

class LandmarkGrid {
 public:
  explicit LandmarkGrid(double cell = 4.0) : cell_(cell) {}

  // Inserts landmark `index` at p, or moves it there.
  void move(int index, const Eigen::Vector3d& p) {
    const std::int64_t key = keyOf(p);
    if (index >= static_cast<int>(cell_of_.size())) cell_of_.resize(index + 1, kNone);
    if (cell_of_[index] == key) return;
    if (cell_of_[index] != kNone) {
      auto& list = cells_[cell_of_[index]];
      for (auto& e : list)
        if (e == index) {
          e = list.back();
          list.pop_back();
          break;
        }
    }
    cells_[key].push_back(index);
    cell_of_[index] = key;
  }

  // Landmarks in cells within `radius` of p (a superset of those within radius). Visits
  // min(cells in the window, occupied cells): a far object or huge radius (whose window has
  // ~(radius / cell)^2 cells) costs a scan of the occupied cells, never more.
  void near(const Eigen::Vector3d& p, double radius, std::vector<int>& out) const {
    const long x0 = cellCoord(p.x() - radius), x1 = cellCoord(p.x() + radius);
    const long y0 = cellCoord(p.y() - radius), y1 = cellCoord(p.y() + radius);
    if (x1 < x0 || y1 < y0) return;  // NaN position or radius
    const double window = (static_cast<double>(x1) - x0 + 1) * (static_cast<double>(y1) - y0 + 1);
    if (window > static_cast<double>(cells_.size())) {
      for (const auto& [key, list] : cells_) {
        const long x = static_cast<std::int32_t>(key >> 32), y = static_cast<std::int32_t>(key & 0xffffffffLL);
        if (x >= x0 && x <= x1 && y >= y0 && y <= y1) out.insert(out.end(), list.begin(), list.end());
      }
      return;
    }
    for (long x = x0; x <= x1; ++x)
      for (long y = y0; y <= y1; ++y) {
        const auto it = cells_.find(pack(x, y));
        if (it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
      }
  }

 private:
  static constexpr std::int64_t kNone = INT64_MIN;
  static constexpr long kFar = 0x7fffffffL;
  // Cell coordinates fit 32 bits (+-8.6e9 m at 4 m cells); beyond, and for NaN, they clamp.
  long cellCoord(double v) const {
    const double c = std::floor(v / cell_);
    if (std::isnan(c)) return kFar;
    return static_cast<long>(std::clamp(c, -static_cast<double>(kFar), static_cast<double>(kFar)));
  }
  static std::int64_t pack(long x, long y) {
    return static_cast<std::int64_t>((static_cast<std::uint64_t>(x) << 32) ^ (static_cast<std::uint64_t>(y) & 0xffffffffULL));
  }
  std::int64_t keyOf(const Eigen::Vector3d& p) const { return pack(cellCoord(p.x()), cellCoord(p.y())); }

  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
  std::vector<std::int64_t> cell_of_;
};

}  // namespace slide::backend
