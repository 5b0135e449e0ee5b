#pragma once
// Spreading a new loop closure's error along its loop before the full solve: a pose graph of
// the loop's key poses alone, whose edges are the current estimate's relative poses (so the
// shape the landmarks gave the trajectory is kept) and the loop closure. The full solve then
// starts next to its solution instead of from a trajectory that still misses the loop by the
// accumulated drift, and needs fewer iterations.
#include <vector>

#include "backend/factors.h"

namespace slide {

struct LoopSpreadNoise {
  double translation_floor = 0.005, translation_per_m = 0.01;  // per edge: max(floor, per_m * length)
  double rotation_floor = 0.0005, rotation_per_m = 0.001;
};

// poses: one robot's current key poses from the loop's older end (index 0, held fixed) to its
// latest; b: index of the newer end; T_a_b: the loop closure. Returns the corrected poses.
std::vector<Pose> spreadLoopError(const std::vector<Pose>& poses, int b, const Pose& T_a_b, const PoseSigma& loop_sigma,
                                  const LoopSpreadNoise& noise);

}  // namespace slide
