#pragma once
// Spreading new loop closures' error along their loops before the full solve: a pose graph of
// the robot's key poses since the oldest loop's start, whose edges are the current estimate's
// relative poses (so the shape the landmarks gave the trajectory is kept), the new closures
// and the closures already in the graph there (so what they hold stays held). The full solve then
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

// The spread of one robot's new loop closures as a full solve carries it out on its snapshot's
// values (off the update path): its key-pose variables from the oldest new closure's older end
// (chain[0], held fixed) to its latest; older key poses that closures already in the graph reach
// from inside the chain (held fixed); and the closures — the new ones and those already in the
// graph with an end in the chain, which the spread keeps as they are met, instead of bending
// what they hold to close the new ones.
struct LoopSpread {
  struct Closure {
    int a = 0, b = 0;  // indices into chain, or -(k + 1) for fixed[k]
    Pose T_a_b = Pose::Identity();
  };
  std::vector<int> chain;
  std::vector<int> fixed;
  std::vector<Closure> closures;
};
// A landmark's variable, shape and the key-pose variables that observed it.
struct LandmarkObservers {
  int var = 0;
  Shape shape = Shape::Ellipsoid;
  std::vector<int> observers;
};

// chain: one robot's current key poses from the oldest new closure's older end (index 0, held
// fixed) to its latest; fixed: older key poses closures reach; closures index both as
// LoopSpread does. A pose graph whose edges are the chain's current relative poses (weighted by
// `noise`) and the closures (loop_sigma). Returns the corrected chain.
std::vector<Pose> spreadLoopError(const std::vector<Pose>& chain, const std::vector<Pose>& fixed,
                                  const std::vector<LoopSpread::Closure>& closures, const PoseSigma& loop_sigma,
                                  const LoopSpreadNoise& noise);

// Each spread in turn on `values` (variables by index, as FactorGraph::Values): its chain
// corrected by spreadLoopError, then every landmark moved with its least-moved observer (those
// seen from before the chain stay).
void spreadLoops(std::vector<std::array<double, 7>>& values, const std::vector<LoopSpread>& spreads,
                 const std::vector<LandmarkObservers>& landmarks, const PoseSigma& loop_sigma,
                 const LoopSpreadNoise& noise);

// Moves a landmark's block (pose, cylinder or point, as the graph holds it) by C.
void moveLandmarkBlock(double* v, Shape shape, const Pose& C);

}  // namespace slide::backend
