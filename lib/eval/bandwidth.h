#pragma once
// Communication cost figures of the paper: bytes sent per landmark and per metre travelled.
#include <cstddef>

namespace slide::eval {

struct BandwidthFigures {
  double bytes = 0;
  double bytes_per_landmark = 0;  // NaN without landmarks
  double bytes_per_metre = 0;     // NaN without travel
};

BandwidthFigures bandwidthFigures(double bytes, std::size_t landmarks, double metres_travelled);

}  // namespace slide::eval
