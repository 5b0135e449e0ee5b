#pragma once
// Spreading a new loop closure's error along its loop before the full solve: a pose graph of
// the loop's key poses alone, whose edges are the current estimate's relative poses (so the
// shape the landmarks gave the trajectory is kept) and the loop closure. The full solve then
// starts next to its solution instead of from a trajectory that still misses the loop by the
// accumulated drift, and needs fewer iterations.
#include <array>
#include <vector>

#include "backend/factors.h"
#include "objects/object.h"

namespace slide::backend {

struct LoopSpreadNoise {
  double translation_floor = 0.005, translation_per_m = 0.01;  // per edge: max(floor, per_m * length)
  double rotation_floor = 0.0005, rotation_per_m = 0.001;
};

// A loop closure's spread as a full solve carries it out on its snapshot's values (off the
// update path): one robot's key-pose variables from the loop's older end (vars[0]) to its
// latest, the index of the newer end, and the closure.
struct LoopSpread {
  std::vector<int> vars;
  int b = 0;
  Pose T_a_b = Pose::Identity();
};
// A landmark's variable, shape and the key-pose variables that observed it.
struct LandmarkObservers {
  int var = 0;
  Shape shape = Shape::Ellipsoid;
  std::vector<int> observers;
};

// poses: one robot's current key poses from the loop's older end (index 0, held fixed) to its
// latest; b: index of the newer end; T_a_b: the loop closure. Returns the corrected poses.
std::vector<Pose> spreadLoopError(const std::vector<Pose>& poses, int b, const Pose& T_a_b, const PoseSigma& loop_sigma,
                                  const LoopSpreadNoise& noise);

// Each spread in turn on `values` (variables by index, as FactorGraph::Values): its key poses
// corrected by spreadLoopError, then every landmark moved with its least-moved observer (those
// seen from before the loop stay).
void spreadLoops(std::vector<std::array<double, 7>>& values, const std::vector<LoopSpread>& loops,
                 const std::vector<LandmarkObservers>& landmarks, const PoseSigma& loop_sigma,
                 const LoopSpreadNoise& noise);

// Moves a landmark's block (pose, cylinder or point, as the graph holds it) by C.
void moveLandmarkBlock(double* v, Shape shape, const Pose& C);

}  // namespace slide::backend
