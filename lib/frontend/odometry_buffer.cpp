#include "frontend/odometry_buffer.h"

#include <cstdlib>

namespace slide::frontend {

void OdometryBuffer::add(std::int64_t utime, const Pose& T) {
  if (!T.matrix().allFinite()) return;
  poses_[utime] = T;
  while (poses_.size() > capacity_) poses_.erase(poses_.begin());
}

std::optional<Pose> OdometryBuffer::at(std::int64_t utime) const {
  if (poses_.empty()) return std::nullopt;
  const auto hi = poses_.lower_bound(utime);
  if (hi != poses_.end() && hi->first == utime) return hi->second;
  if (hi == poses_.begin()) {
    if (hi->first - utime <= tolerance_us_) return hi->second;
    return std::nullopt;
  }
  const auto lo = std::prev(hi);
  if (hi == poses_.end()) {
    if (utime - lo->first <= tolerance_us_) return lo->second;
    return std::nullopt;
  }
  const double s = double(utime - lo->first) / double(hi->first - lo->first);
  return interpolatePose(lo->second, hi->second, s);
}

bool OdometryBuffer::hopeless(std::int64_t utime) const {
  return !poses_.empty() && poses_.rbegin()->first > utime + tolerance_us_ && !at(utime);
}

}  // namespace slide::frontend
