#include "frontend/keypose.h"

#include <cmath>

namespace slide::frontend {

std::optional<KeyPoseBundle> KeyPoseBundler::process(const FrameInstances& frame, InputIssues& issues) {
  if (!frame.odom_pose.matrix().allFinite()) {
    issues.count("non-finite odometry pose");
    return std::nullopt;
  }
  tracker_.update(frame, issues);
  ++frames_since_key_;
  const Pose& T = frame.odom_pose;
  if (next_seq_ > 0) travelled_ += (T.translation() - last_frame_.translation()).norm();
  last_frame_ = T;
  const Pose rel = last_key_.inverse() * T;
  const double turned = std::abs(yawOf(rel.linear())) * 180.0 / M_PI;
  if (next_seq_ > 0 && travelled_ < params_.distance && turned < params_.yaw_deg) return std::nullopt;

  KeyPoseBundle b;
  b.seq = next_seq_++;
  b.utime = frame.utime;
  b.odom_pose = T;
  b.relative_odom = b.seq == 0 ? Pose::Identity() : rel;
  for (int i = 0; i < 6; ++i) b.odom_sigma[i] = params_.sigma_min[i] + params_.sigma_per_m[i] * travelled_;
  // Every track seen since the previous key pose: one confirmed in between and lost just
  // before this key pose is no less an observation.
  b.objects = tracker_.objectsInBody(T, b.seq == 0 ? 0 : frames_since_key_);
  frames_since_key_ = 0;
  last_key_ = T;
  travelled_ = 0;
  return b;
}

}  // namespace slide::frontend
