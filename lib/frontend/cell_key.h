#pragma once
// Cubic cells of a point cloud as hash keys: a point's integer cell coordinates, and the three
// of them packed in 21 bits each (+-2^20 cells: +-70 km at 0.07 m), so none alias.
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

#include <Eigen/Core>

namespace slide::frontend {

// The cell of `p` (cells of side 1 / inv_cell); none for a point beyond +-2^20 cells (a return
// kilometres up) or not finite.
inline std::optional<std::array<int, 3>> cellOf(const Eigen::Vector3f& p, double inv_cell) {
  constexpr double kMaxCell = 1 << 20;
  std::array<int, 3> c{};
  for (int k = 0; k < 3; ++k) {
    const double v = std::floor(p[k] * inv_cell);
    if (!(std::abs(v) < kMaxCell)) return std::nullopt;
    c[k] = static_cast<int>(v);
  }
  return c;
}

inline std::int64_t cellKey(int x, int y, int z) {
  constexpr std::int64_t kMask = (1 << 21) - 1;
  return ((static_cast<std::int64_t>(x) & kMask) << 42) | ((static_cast<std::int64_t>(y) & kMask) << 21) |
         (static_cast<std::int64_t>(z) & kMask);
}

}  // namespace slide::frontend
