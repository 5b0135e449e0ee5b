#pragma once
// Summary statistics of a sample of non-negative errors (metres, degrees, ...).
#include <cstddef>
#include <vector>

namespace slide::eval {

struct ErrorStats {
  std::size_t count = 0;
  double rmse = 0, mean = 0, median = 0, std = 0, min = 0, max = 0;
};

// All zero for an empty sample; std is the population standard deviation.
ErrorStats errorStats(const std::vector<double>& errors);

}  // namespace slide::eval
