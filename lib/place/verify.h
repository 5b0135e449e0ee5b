#pragma once
// Turning a hypothesis T_a_b into a decision: class- and size-consistent one-to-one matches
// under T, 4-DoF refinement on them, and an acceptance test against what chance would give.
#include "place/landmark_index.h"
#include "place/place_result.h"

namespace slide {

struct VerifyParams {
  double match_radius = 0.6;       // metres (3-D) between a landmark of A and one of B moved by T
  double size_tolerance = 1.0;     // metres, see sizesAgree()
  std::size_t min_inliers = 5;     // fewer matches never make a transform
  double min_inlier_ratio = 0.3;   // of B's landmarks that land where A has landmarks
  double significance = 5.0;       // inliers >= chance + significance * sqrt(chance)
  double robust_scale = 0.3;       // Cauchy scale of the refinement, metres
  int rounds = 3;                  // match / refine rounds
};

// One-to-one matches (greedy by distance) of B's landmarks, moved by T_a_b, to A's landmarks of
// the same class within match_radius whose sizes agree.
std::vector<LandmarkMatch> guidedMatches(const std::vector<Landmark>& a, const LandmarkIndex& index_a,
                                         const std::vector<Landmark>& b, const Pose& T_a_b,
                                         const VerifyParams& params);

// Overlap and chance for the acceptance test: B's landmarks that land within the coverage
// radius of some landmark of A, and the matches expected by chance among them.
struct Overlap {
  std::size_t covered = 0;
  double chance = 0;
};
Overlap overlapOf(const std::vector<Landmark>& a, const LandmarkIndex& index_a, const std::vector<Landmark>& b,
                  const Pose& T_a_b, double match_radius);

// From the hypothesis: match, refine (robust 4-DoF), repeat; then accept or reject, filling
// out.found, T_a_b, inliers, residual_rms, chance_inliers and reason.
void refineAndDecide(const std::vector<Landmark>& a, const LandmarkIndex& index_a, const std::vector<Landmark>& b,
                     const Pose& hypothesis, const VerifyParams& params, PlaceResult& out);

}  // namespace slide
