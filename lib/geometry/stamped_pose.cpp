#include "geometry/stamped_pose.h"

#include <algorithm>
#include <cmath>

namespace slide {

PoseMiss poseAtTime(const std::vector<StampedPose>& traj, double t, double max_gap_s, Pose& out) {
  if (traj.empty() || !std::isfinite(t)) return PoseMiss::OutsideSpan;
  const auto hi = std::lower_bound(traj.begin(), traj.end(), t, [](const StampedPose& p, double v) { return p.t < v; });
  if (hi != traj.end() && hi->t - t <= kSameTimeS) return out = hi->pose, PoseMiss::None;
  if (hi != traj.begin() && t - std::prev(hi)->t <= kSameTimeS) return out = std::prev(hi)->pose, PoseMiss::None;
  if (hi == traj.begin() || hi == traj.end()) return PoseMiss::OutsideSpan;
  const StampedPose& lo = *std::prev(hi);
  const double dt = hi->t - lo.t;
  if (!(dt <= max_gap_s)) return PoseMiss::Gap;
  out = interpolatePose(lo.pose, hi->pose, (t - lo.t) / dt);
  return PoseMiss::None;
}

}  // namespace slide
