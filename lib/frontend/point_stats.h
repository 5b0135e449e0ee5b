#pragma once
// Small order statistics on float samples used by the fitters and the segmenters.
#include <algorithm>
#include <cmath>
#include <vector>

namespace slide::frontend {

// q-th quantile (0..1) by nth_element (no interpolation); NaN for an empty sample.
// Reorders `v`.
inline double quantileInPlace(std::vector<double>& v, double q) {
  if (v.empty()) return std::nan("");
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(std::max(0.0, q) * (v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

}  // namespace slide::frontend
