#pragma once
// Recent odometry poses by time, for stamping sensor frames that arrive separately from the
// odometry: interpolated between the two poses around a frame's time.
#include <cstdint>
#include <map>
#include <optional>

#include "geometry/pose.h"

namespace slide::frontend {

class OdometryBuffer {
 public:
  explicit OdometryBuffer(std::size_t capacity = 4000, std::int64_t tolerance_us = 20000)
      : capacity_(capacity), tolerance_us_(tolerance_us) {}

  void add(std::int64_t utime, const Pose& T_odom_body);
  // Pose at `utime`: interpolated inside the buffered span, the nearest end pose within the
  // tolerance outside it, nullopt otherwise.
  std::optional<Pose> at(std::int64_t utime) const;
  // True when odometry newer than utime + tolerance exists but at(utime) fails: the frame
  // will never get a pose (it is older than the buffer).
  bool hopeless(std::int64_t utime) const;
  bool empty() const { return poses_.empty(); }

 private:
  std::size_t capacity_;
  std::int64_t tolerance_us_;
  std::map<std::int64_t, Pose> poses_;
};

}  // namespace slide::frontend
