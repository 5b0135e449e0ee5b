#pragma once
// Time-stamped poses (a trajectory sampled at its own times) and the pose at any time between
// two samples: linear in translation, slerp in rotation (interpolatePose). A time outside the
// samples' span, or between two samples further apart than a limit, has no pose: the caller
// drops what needs it, it never gets a guessed one.
// Vocabulary: in namespace slide itself, not slide::geometry, as every area uses it (README).
#include <vector>

#include "geometry/pose.h"

namespace slide {

struct StampedPose {
  double t = 0;  // seconds
  Pose pose = Pose::Identity();
};

// Why poseAtTime found no pose.
enum class PoseMiss { None, OutsideSpan, Gap };

// Samples closer than this to t count as taken at t (TUM files keep microseconds).
constexpr double kSameTimeS = 1.5e-6;

// Pose of `trajectory` (sorted by time, non-decreasing) at time t into `out`. A sample within
// kSameTimeS of t is returned as it is; otherwise the two samples around t are interpolated
// when they are at most max_gap_s apart. Returns PoseMiss::None on success.
PoseMiss poseAtTime(const std::vector<StampedPose>& trajectory, double t, double max_gap_s, Pose& out);

}  // namespace slide
