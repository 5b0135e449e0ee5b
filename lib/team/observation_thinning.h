#pragma once
// Which of a robot's own observations go on the team bus. A track's observation is shared when
// it adds information for the team: the first `min_shares` observations of the track (a peer's
// optimizer, like the robot's own, confirms a landmark from that many), or the robot moved at
// least `travel_m` or turned at least `turn_deg` since the last shared observation of that
// track, or the track's class, shape or size (any extent by `size_change_m`) changed since.
// Everything else stays on the robot (its own stack and journal keep the full bundle); key
// poses keep their odometry even when no object is left, so the chain stays complete.
//
// The decision depends only on the bundles fed so far, in sequence order: replaying the same
// stream (after a restart, from the journal) gives the same shared bundles, byte for byte.
#include <map>

#include "objects/keypose_bundle.h"

namespace slide::team {

struct ThinningPolicy {
  bool enabled = true;
  double travel_m = 10.0;
  double turn_deg = 45.0;
  double size_change_m = 1.0;
  int min_shares = 3;
};

class ObservationThinning {
 public:
  explicit ObservationThinning(ThinningPolicy policy) : policy_(policy) {}
  // The bundle as shared: `b` with only the objects worth sharing (all when disabled).
  KeyPoseBundle thin(const KeyPoseBundle& b);

 private:
  struct Shared {
    Pose odom_pose;  // where the robot was when the track was last shared
    int class_id;
    std::size_t shape;
    Eigen::Vector3d extent;
    int shares;
  };
  bool worthSharing(const Object& o, const Pose& odom_pose) const;

  ThinningPolicy policy_;
  std::map<std::int64_t, Shared> last_;  // by track id
};

}  // namespace slide::team
