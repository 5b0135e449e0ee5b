#pragma once
// Order statistics for timing figures.
#include <vector>

namespace slide::bench {

// q-th quantile (0..1) with linear interpolation; NaN for an empty sample.
double quantile(std::vector<double> values, double q);
inline double median(const std::vector<double>& v) { return quantile(v, 0.5); }
double mean(const std::vector<double>& v);

}  // namespace slide::bench
