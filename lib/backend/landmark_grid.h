#pragma once
// A uniform 2-D grid (x, y) of landmark indices for association look-ups; positions move
// after solves, so entries are re-bucketed with move().
#include <Eigen/Core>
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

  // Landmarks in cells within `radius` of p (a superset of those within radius).
  void near(const Eigen::Vector3d& p, double radius, std::vector<int>& out) const {
    const long x0 = cellCoord(p.x() - radius), x1 = cellCoord(p.x() + radius);
    const long y0 = cellCoord(p.y() - radius), y1 = cellCoord(p.y() + radius);
    for (long x = x0; x <= x1; ++x)
      for (long y = y0; y <= y1; ++y) {
        const auto it = cells_.find(pack(x, y));
        if (it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
      }
  }

 private:
  static constexpr std::int64_t kNone = INT64_MIN;
  long cellCoord(double v) const { return static_cast<long>(std::floor(v / cell_)); }
  static std::int64_t pack(long x, long y) { return (static_cast<std::int64_t>(x) << 32) ^ (y & 0xffffffffLL); }
  std::int64_t keyOf(const Eigen::Vector3d& p) const { return pack(cellCoord(p.x()), cellCoord(p.y())); }

  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
  std::vector<std::int64_t> cell_of_;
};

}  // namespace slide::backend
