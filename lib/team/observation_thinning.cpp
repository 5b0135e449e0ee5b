#include "team/observation_thinning.h"

#include <cmath>

namespace slide::team {

bool ObservationThinning::worthSharing(const Object& o, const Pose& odom_pose) const {
  auto it = last_.find(o.id);
  if (it == last_.end()) return true;
  const Shared& s = it->second;
  if (s.shares < policy_.min_shares) return true;
  if (s.class_id != o.class_id || s.shape != o.model.index()) return true;
  if (((o.extent() - s.extent).cwiseAbs().array() >= policy_.size_change_m).any()) return true;
  const Pose moved = s.odom_pose.inverse() * odom_pose;
  if (moved.translation().norm() >= policy_.travel_m) return true;
  return Eigen::AngleAxisd(moved.linear()).angle() >= policy_.turn_deg * M_PI / 180.0;
}

KeyPoseBundle ObservationThinning::thin(const KeyPoseBundle& b) {
  if (!policy_.enabled) return b;
  KeyPoseBundle out = b;
  out.objects.clear();
  for (const Object& o : b.objects) {
    if (!worthSharing(o, b.odom_pose)) continue;
    const auto it = last_.find(o.id);
    last_[o.id] = {b.odom_pose, o.class_id, o.model.index(), o.extent(), it == last_.end() ? 1 : it->second.shares + 1};
    out.objects.push_back(o);
  }
  return out;
}

}  // namespace slide::team
