#pragma once
// Order statistics for timing figures, and a least-squares slope.
#include <vector>

namespace slide::bench {

// q-th quantile (0..1) with linear interpolation; NaN for an empty sample.
double quantile(std::vector<double> values, double q);
inline double median(const std::vector<double>& v) { return quantile(v, 0.5); }
double mean(const std::vector<double>& v);
// Least-squares slope of y over x (same length); NaN for fewer than 3 pairs or constant x.
double slope(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace slide::bench
