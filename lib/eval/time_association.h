#pragma once
// Pairs the poses of two timestamped trajectories (e.g. TUM files) that describe the same
// instant, as evo's synchronisation does: nearest stamps within a maximum difference.
#include <cstddef>
#include <utility>
#include <vector>

#include "io/tum_trajectory.h"

namespace slide::eval {

// (index in est, index in ref) pairs, one-to-one, ordered by est index. Stamps of est are
// shifted by `offset` first. Candidate pairs are each est stamp's nearest ref stamp; when two
// est stamps want the same ref stamp the closer one wins. Pairs further apart than max_dt
// (seconds) are dropped. Stamps need not be sorted.
std::vector<std::pair<std::size_t, std::size_t>> associateByTime(const std::vector<double>& est_t,
                                                                 const std::vector<double>& ref_t, double max_dt,
                                                                 double offset = 0.0);

struct AssociatedPoses {
  std::vector<double> t;  // reference stamps
  std::vector<Pose> est, ref;
};

// The poses of both trajectories at the associated stamps; throws std::invalid_argument when
// fewer than `min_pairs` pairs are found (the message gives both time ranges).
AssociatedPoses associatePoses(const std::vector<StampedPose>& est, const std::vector<StampedPose>& ref,
                               double max_dt, double offset = 0.0, std::size_t min_pairs = 2);

}  // namespace slide::eval
