#pragma once
// The loop closer's logic, free of any middleware: holds the robot's own map and trajectory and
// its peers' maps, and on poll() runs what is due —
//  * intra-robot: when the current key pose comes near an old one, the objects first seen
//    recently around it are matched against the objects first seen long ago (duplicates left
//    by drift); the match moves the recent ones onto the old ones in the robot's frame, and the
//    closure given is what that says about two key poses' bodies (see LoopClosure::T_a_b);
//  * inter-robot: the own map against each peer's map, every period, staggered between peers
//    and robots, re-checked whenever either map changed.
// Every result passes through a consensus filter per peer (per place for intra-robot).
#include <functional>
#include <map>

#include "place/consensus_filter.h"
#include "place/place_config.h"

namespace slide::place {

struct LoopCloserParams {
  int robot = 0;
  PlaceMethod method = PlaceMethod::SlideGraph;
  PlaceConfig place;
  ConsensusParams consensus;
  double inter_period_s = 5.0;         // each peer is re-checked at most this often
  double stagger_s = 1.0;              // first checks of peers are spread by this much
  double intra_period_s = 2.0;
  double intra_trigger_radius_m = 10.0; // the current key pose this close to an old one...
  int intra_min_keypose_gap = 30;       // ...at least this many key poses older triggers a check
  double intra_local_radius_m = 25.0;   // objects within this of the current pose form the sub-maps
  // Both radii grow by this fraction of the path driven between the old key pose and the
  // current one: the own estimate can be that far off where the robot returns after a long way.
  double intra_drift_fraction = 0.0;
  std::size_t min_objects = 6;          // per map or sub-map
  std::size_t max_map_objects = 50000;  // a map update with more objects is dropped (counted)
};

// What the loop closer refused or gave up on, for the daemon's log.
struct LoopCloserCounts {
  long oversized_maps = 0;   // map updates over max_map_objects, dropped (the previous map stays)
  long budget_exceeded = 0;  // checks that ran out of their place-recognition time budget
};

struct LoopClosure {
  int robot_a = 0, robot_b = 0;
  int keypose_a = -1, keypose_b = -1;  // intra-robot: old and current key pose sequence numbers
  PlaceMethod method = PlaceMethod::SlideGraph;
  // Held (consensus) transform. Inter-robot: B's frame into A's. Intra-robot: the pose of key
  // pose b's body in key pose a's body, as the optimizer takes it: P_a^-1 M P_b with M the match
  // (recent objects onto old ones, in the robot's frame) and P the key poses given with the map.
  Pose T_a_b = Pose::Identity();
  PlaceResult result;                  // the raw result of this check
  std::vector<std::pair<std::int64_t, std::int64_t>> inliers;  // object ids (map A, map B)
  ConsensusFilter::Outcome outcome = ConsensusFilter::Outcome::Pending;
};

struct KeyPose {
  int seq = 0;
  Pose pose = Pose::Identity();
};

class LoopCloser {
 public:
  explicit LoopCloser(LoopCloserParams params) : params_(std::move(params)) {}

  // The robot's own map in its own frame; objects need stable ids. A map with more than
  // max_map_objects objects is dropped and counted (false); the previous one stays.
  bool setOwnMap(const ObjectMap& map, double now_s);
  // A peer's map in the peer's own frame; dropped like the own map when too large.
  bool setPeerMap(int robot, const ObjectMap& map, double now_s);
  // The robot's key poses (own frame), oldest first.
  void setTrajectory(std::vector<KeyPose> keyposes);

  // Runs the checks that are due (at most one inter-robot check per call, to spread load) and
  // returns their outcomes: found transforms, accepted, refined, replaced or held back.
  std::vector<LoopClosure> poll(double now_s);

  // Why the last check of each kind did not produce a transform (for logs and tests).
  const std::string& lastReason() const { return last_reason_; }
  const LoopCloserCounts& counts() const { return counts_; }

 private:
  struct Peer {
    ObjectMap map;
    int version = 0, checked_version = -1, own_checked_version = -1;
    double next_due = 0;
    ConsensusFilter filter;
  };
  std::optional<LoopClosure> checkPeer(int robot, Peer& peer);
  // One intra-robot place (old key poses by min_keypose_gap): its consensus, over closures all
  // expressed between the key poses of its first check (a closure from the match of another
  // check's sub-maps: P_a^-1 M P_b with this pair's key poses). A place's closure is fixed once
  // given: after the optimizer takes it in, the objects there move with it (duplicates merged,
  // recent objects onto old ones) and later matches measure the optimizer's own compromise, not
  // the place. A later match that agrees re-sends the given closure unchanged (confirmed: the
  // optimizer replaces it and solves again); one that disagrees is held back.
  struct IntraPlace {
    ConsensusFilter filter;
    int seq_a = -1, seq_b = -1;
    std::optional<Pose> given;
  };
  std::optional<LoopClosure> checkIntra();
  // Place recognition of the sub-maps (fills result and inliers), then the consensus filter
  // over `T` (the result's transform, or what it says in another form) when found. With
  // contest_held, an ambiguous result's stronger alignment also goes to the filter
  // (ConsensusFilter::add, may_establish false; feedsAmbiguous says when): it may replace the
  // held transform (ConsensusParams::ambiguous_may_replace) or confirm a pending one
  // (ambiguous_may_confirm). Inter-robot checks contest; intra-robot ones do not.
  LoopClosure run(const ObjectMap& a, const std::vector<std::size_t>& ia, const ObjectMap& b,
                  const std::vector<std::size_t>& ib, ConsensusFilter& filter,
                  const std::function<Pose(const Pose&)>& express = nullptr, bool contest_held = false);
  const KeyPose* keyPose(int seq) const;

  LoopCloserParams params_;
  ObjectMap own_;
  int own_version_ = 0;
  std::map<std::int64_t, int> first_seen_;  // object id -> key pose seq when first in the map
  std::vector<KeyPose> keyposes_;
  std::map<int, Peer> peers_;
  std::map<int, IntraPlace> intra_places_;  // keyed by old key pose / gap
  double next_intra_ = 0;
  std::string last_reason_;
  LoopCloserCounts counts_;
};

}  // namespace slide::place
