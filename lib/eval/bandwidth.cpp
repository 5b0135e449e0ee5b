#include "eval/bandwidth.h"

#include <limits>
#include <stdexcept>

namespace slide::eval {

BandwidthFigures bandwidthFigures(double bytes, std::size_t landmarks, double metres_travelled) {
  if (bytes < 0 || metres_travelled < 0) throw std::invalid_argument("bandwidth: negative bytes or distance");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BandwidthFigures f;
  f.bytes = bytes;
  f.bytes_per_landmark = landmarks ? bytes / double(landmarks) : nan;
  f.bytes_per_metre = metres_travelled > 0 ? bytes / metres_travelled : nan;
  return f;
}

}  // namespace slide::eval
