#include "eval/error_stats.h"

#include <algorithm>
#include <cmath>

#include "bench/stats.h"

namespace slide::eval {

ErrorStats errorStats(const std::vector<double>& errors) {
  ErrorStats s;
  s.count = errors.size();
  if (errors.empty()) return s;
  double sq = 0;
  for (double e : errors) sq += e * e;
  s.rmse = std::sqrt(sq / errors.size());
  s.mean = bench::mean(errors);
  s.median = bench::median(errors);
  double var = 0;
  for (double e : errors) var += (e - s.mean) * (e - s.mean);
  s.std = std::sqrt(var / errors.size());
  const auto [lo, hi] = std::minmax_element(errors.begin(), errors.end());
  s.min = *lo;
  s.max = *hi;
  return s;
}

}  // namespace slide::eval
