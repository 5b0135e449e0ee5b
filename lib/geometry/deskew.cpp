#include "geometry/deskew.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace slide {

std::vector<uint8_t> deskewSweep(std::vector<Eigen::Vector3f>& xyz, const std::vector<double>& dt, double t_ref,
                                 const PoseLookup& pose_at, double resolution_s) {
  if (xyz.size() != dt.size()) throw std::invalid_argument("deskew: points and times differ in count");
  std::vector<uint8_t> ok(xyz.size(), 0);
  if (xyz.empty()) return ok;
  Pose T_ref;
  if (pose_at(t_ref, T_ref) != PoseMiss::None) return ok;
  const auto [lo_it, hi_it] = std::minmax_element(dt.begin(), dt.end());
  const double lo = *lo_it, step = resolution_s > 0 ? resolution_s : 1e-4;
  // A sweep lasts well under a second; longer spans are clamped to 10^5 grid cells.
  const std::size_t cells = std::min<std::size_t>(100000, static_cast<std::size_t>((*hi_it - lo) / step) + 1);
  const double cell = cells > 1 ? (*hi_it - lo) / static_cast<double>(cells - 1) : 0.0;
  std::vector<std::optional<Eigen::Isometry3f>> grid(cells);
  std::vector<uint8_t> looked(cells, 0);
  const Pose T_ref_inv = T_ref.inverse();
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    const std::size_t g = cell > 0 ? std::min(cells - 1, static_cast<std::size_t>(std::lround((dt[i] - lo) / cell))) : 0;
    if (!looked[g]) {
      looked[g] = 1;
      Pose T;
      if (pose_at(t_ref + lo + cell * static_cast<double>(g), T) == PoseMiss::None) grid[g] = (T_ref_inv * T).cast<float>();
    }
    if (!grid[g]) continue;
    xyz[i] = *grid[g] * xyz[i];
    ok[i] = 1;
  }
  return ok;
}

}  // namespace slide
