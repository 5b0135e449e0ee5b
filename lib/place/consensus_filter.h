#pragma once
// Consensus over repeated place-recognition results for one pair of maps (e.g. own map vs a
// peer's). Results that agree with the held transform refine it (inlier-weighted mean); a
// result that disagrees is held back, and replaces the held transform only once repeated
// attempts agree with it more often than with the held one over a recent window. This guards
// against aliased scenes (two similar rooms) where a single answer can be wrong.
#include <deque>
#include <map>
#include <optional>

#include "geometry/pose.h"
#include "place/place_result.h"

namespace slide::place {

struct ConsensusParams {
  double trans_tol = 1.0;         // metres: two results agree within this translation...
  double yaw_tol_deg = 3.0;       // ...and this yaw difference
  int initial_confirmations = 1;  // agreeing results needed before the first transform is held
  int change_confirmations = 3;   // agreeing results needed to replace the held transform
  int window = 10;                // recent results that count as support
  // Results that may not establish (add()) count once a transform is held; false: ignored.
  bool ambiguous_may_replace = true;
  // ... and, against the held transform, only when they outweigh every result that made or
  // refined it (later, stronger evidence: more inliers) and lie farther from it than this
  // (translation) or this yaw: another alignment, not a variant of the held one (a bent map
  // aligned on another part of the overlap, as the rival test of verify.h tells them apart).
  double contest_min_offset = 3.0;
  double contest_min_yaw_deg = 5.0;
  // Before a transform is held, such a result counts as one confirmation of a pending alignment
  // it agrees with (one that a result that may establish started) when it has at least that
  // alignment's inliers; it never starts one. (Only SlideGraph's results: feedsAmbiguous.)
  bool ambiguous_may_confirm = true;
};

class ConsensusFilter {
 public:
  enum class Outcome {
    Accepted,  // first transform held
    Refined,   // agreed with the held transform, which was refined
    Replaced,  // a repeatedly confirmed contender replaced the held transform
    Pending,   // held back: disagrees with the held one (or not yet confirmed)
  };
  struct Update {
    Outcome outcome = Outcome::Pending;
    Pose T = Pose::Identity();  // the held transform after this update (meaningful unless Pending)
    int support = 0;            // recent results agreeing with the result just added
  };

  explicit ConsensusFilter(ConsensusParams params = {}) : params_(params) {}

  // Adds a found transform with its weight (e.g. inlier count, > 0). A result that may not
  // establish (the stronger alignment of a check that found another nearly as strong) counts
  // only once a transform is held: as support for the alignment it agrees with (the held one:
  // support only, neither refined nor re-sent, Pending), so that another alignment every later
  // check finds the stronger replaces the held one (an alias of a periodic scene, held while
  // the maps were small, is then met by checks that call it the weaker); it never makes the
  // first transform, but before one is held it confirms a pending alignment it agrees with
  // (ambiguous_may_confirm: the same alignment found the stronger again, as in TCAFF's
  // hypotheses kept while they stay consistent); one near the held transform
  // (contest_min_offset) or weaker than the strongest result behind it is ignored. Ignored
  // altogether without ambiguous_may_replace.
  Update add(const Pose& T, double weight, bool may_establish = true);
  // The held transform, if any.
  std::optional<Pose> held() const;

 private:
  struct Cluster {
    Eigen::Vector3d t_sum = Eigen::Vector3d::Zero();
    double cos_sum = 0, sin_sum = 0, weight = 0;
    double strongest = 0;  // the largest weight of one result
    Pose mean() const;
  };
  int supportOf(int id) const;
  // Records a result of cluster `id` among the recent ones; forgets contenders left without support.
  void remember(int id);
  // An ambiguous result agreeing with pending cluster `id` (nothing held): support only.
  Update confirm(int id);

  ConsensusParams params_;
  std::map<int, Cluster> clusters_;
  std::deque<int> recent_;  // cluster id of each recent result, newest last
  int held_ = -1;
  int next_id_ = 0;
};

const char* outcomeName(ConsensusFilter::Outcome o);

// Whether an ambiguous result of `method` (no transform: another alignment nearly as strong)
// goes to `filter` (as may_establish false): always once it holds a transform; before, only
// SlideGraph's. SlideMatch's confirmed wrong alignments on the place bench (realistic urban:
// published wrong 1 -> 3; repeated rooms: a false positive).
bool feedsAmbiguous(PlaceMethod method, const ConsensusFilter& filter);

}  // namespace slide::place
