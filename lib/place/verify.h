#pragma once
// Turning a hypothesis T_a_b into a decision: class- and size-consistent one-to-one matches
// under T, 4-DoF refinement on them, and an acceptance test against what chance would give.
#include "place/landmark_index.h"
#include "place/place_result.h"

namespace slide::place {

struct VerifyParams {
  // A landmark of A and one of B moved by T match when their horizontal distance is within
  // match_radius and their heights differ by at most match_height: heights are the least
  // certain coordinate of a map (terrain under a trunk's foot, vertical drift, how much of an
  // object was seen), and the chance of a match is counted over the horizontal disc.
  double match_radius = 0.6;       // metres, horizontal
  double match_height = 1.0;       // metres, vertical
  double size_tolerance = 1.0;     // metres, see sizesAgree()
  std::size_t min_inliers = 5;     // fewer matches never make a transform
  double min_inlier_ratio = 0.2;   // of the overlap as the sparser map holds it (refineAndDecide)
  double significance = 5.0;       // inliers >= chance + significance * sqrt(chance)
  double max_yaw_sigma_deg = 1.0;  // the matches' standard error of yaw (residual / spread) at most this
  double robust_scale = 0.3;       // Cauchy scale of the refinement, metres
  int rounds = 3;                  // match / refine rounds
  double rival_separation = 3.0;   // metres: another alignment this far off is a rival (ambiguity test)...
  double rival_ratio = 2.0;        // ...and the answer needs this many times its strength
};

// One-to-one matches (greedy by horizontal distance) of B's landmarks, moved by T_a_b, to A's
// landmarks of the same class within match_radius horizontally and match_height vertically
// whose sizes agree.
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
// How many of `pts`, moved by T, land within the coverage radius of some landmark of the map
// `index` holds (its radius: three times its median spacing, at least four match radii).
std::size_t coveredBy(const std::vector<Landmark>& pts, const Pose& T, const LandmarkIndex& index, double match_radius);

// From the hypothesis: match, refine (robust 4-DoF), repeat; then accept or reject, filling
// out.found, T_a_b, inliers, residual_rms, chance_inliers and reason. The inlier ratio is taken
// over the overlap as the sparser map holds it: B's covered landmarks, or A's landmarks within B's
// coverage when fewer (counted only when B's count would reject). A robot that maps only what its
// short-range camera caught is covered by a LiDAR robot's map, but most of the LiDAR map's
// landmarks around it lie where that camera never looked or detected nothing.
void refineAndDecide(const std::vector<Landmark>& a, const LandmarkIndex& index_a, const std::vector<Landmark>& b,
                     const LandmarkIndex& index_b, const Pose& hypothesis, const VerifyParams& params,
                     PlaceResult& out);

// How well a hypothesis explains B where it overlaps A: inliers times the inlier fraction of the
// covered landmarks (n^2 / covered). An alignment that matches as many landmarks only by laying B
// over much more of A (a street grid shifted by a block) is weaker. By fit, n is the support: each
// inlier weighted by 1 - (d / match radius)^2 for its horizontal residual d, so that an alignment
// whose matches merely fall somewhere in the match disc (an alias of a block grid: 0.34 m off) is
// weaker than one whose matches sit where the map put them (the truth between two good maps:
// 0.16 m off).
double strengthOf(const PlaceResult& r, bool by_fit = false);
// Whether the ambiguity test weighs by fit: only when best's matches fit significantly tighter
// than matches landing anywhere in the disc (their weights average 1/2, spread 1/sqrt(12) each;
// verify.significance standard errors). Between noisy maps (0.25 m per object) the truth's own fit
// is no tighter than an alias's and the weights would only add chance to the test.
bool fitDecides(const PlaceResult& best, const VerifyParams& params);
// Ambiguity: the strongest of the verified `hypotheses` (accepted or not) that are another
// alignment than `best`: they share fewer than half of their matches with it and move the centroid of best's
// inliers in B by more than params.rival_separation (or turn B by more than 5 degrees against
// it); a variant of the same alignment (a bent map aligned on another part of the overlap) is no
// rival. Strongest by fit when fitDecides(best). Null when there is none.
const PlaceResult* rivalOf(const PlaceResult& best, const std::vector<PlaceResult>& hypotheses,
                           const std::vector<Landmark>& b, const VerifyParams& params);
// A scene that aligns nearly as well another way (rooms furnished alike) gives no transform: best
// needs rival_ratio times the rival's strength (by fit when fitDecides). Clears best.found and sets the reason when it
// falls short; true when best stands (or has no rival).
bool standsAgainstRival(const PlaceResult* rival, const VerifyParams& params, PlaceResult& best);

}  // namespace slide::place
