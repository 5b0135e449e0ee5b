#pragma once
// Key poses every configurable travelled distance (or turn), each with one observation bundle:
// the relative odometry since the previous key pose and the tracker's objects in the body frame.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "frontend/tracker.h"
#include "objects/keypose_bundle.h"

namespace slide::frontend {

struct KeyPoseParams {
  double distance = 1.0;   // metres travelled since the previous key pose
  double yaw_deg = 30.0;   // or this much turning
  std::array<double, 6> sigma_min{0.002, 0.002, 0.002, 0.0002, 0.0002, 0.0002};  // x y z roll pitch yaw
  std::array<double, 6> sigma_per_m{0.01, 0.01, 0.01, 0.001, 0.001, 0.001};      // added per metre
};

// Feeds frames to a Tracker and emits a bundle whenever a frame is a key pose (the first
// frame always is). The bundle's robot is left 0: the caller knows whose it is.
class KeyPoseBundler {
 public:
  KeyPoseBundler(Tracker tracker, KeyPoseParams params) : tracker_(std::move(tracker)), params_(params) {}

  std::optional<KeyPoseBundle> process(const FrameInstances& frame, InputIssues& issues);

  const Tracker& tracker() const { return tracker_; }
  int nextSeq() const { return next_seq_; }

 private:
  Tracker tracker_;
  KeyPoseParams params_;
  int next_seq_ = 0;
  int frames_since_key_ = 0;  // frames since the previous key pose, this one included
  Pose last_key_ = Pose::Identity();
  Pose last_frame_ = Pose::Identity();
  double travelled_ = 0;  // path length since the last key pose
};

}  // namespace slide::frontend
