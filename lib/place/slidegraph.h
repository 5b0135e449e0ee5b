#pragma once
// SlideGraph: Delaunay triangles of each map, described by sorted vertex-to-centroid distances
// and vertex classes; candidate triangle pairs from a k-d tree over B's descriptors; their
// vertex correspondences, ranked by votes, become the associations that CLIPPER prunes; the
// surviving clique seeds a 4-DoF alignment that guided matching refines and verifies. A budget
// of the calling thread's CPU time is checked inside the triangulation and association loops
// and between stages: when it runs out the query gives no transform, with budget_exhausted set.
#include "place/clipper.h"
#include "place/verify.h"

namespace slide::place {

struct SlideGraphParams {
  double descriptor_radius = 0.4;         // metres in descriptor space
  std::size_t neighbors_per_simplex = 3;  // candidate B triangles kept per A triangle
  std::size_t max_associations = 2500;    // strongest (most voted) associations given to CLIPPER
  std::uint32_t min_votes = 2;            // associations seen in fewer triangle pairs are dropped...
  std::size_t min_voted = 40;             // ...unless fewer than this many would remain
  bool use_classes = true;                // vertex classes must agree
  std::size_t min_landmarks = 4;          // per map
  int hypotheses = 3;                     // CLIPPER sets tried (each without the previous ones)
  // Small maps (both at most this many landmarks) that give no transform are tried once more
  // with descriptor radius, CLIPPER sigma and epsilon scaled up (noisy real maps; cheap there).
  std::size_t small_map = 200;
  double retry_tolerance_scale = 1.6;
  double budget_ms = 5000;                // thread CPU time budget of one query (the small-map retry included)
  ClipperParams clipper;
  VerifyParams verify;
};

// T_a_b mapping B's frame into A's, or no transform with the reason (budget_exhausted: the
// time budget ran out first). Inlier indices refer to the landmark vectors.
PlaceResult slideGraph(const std::vector<Landmark>& a, const std::vector<Landmark>& b, const SlideGraphParams& params);
// One attempt with exactly these tolerances (slideGraph() adds the small-map retry).
PlaceResult slideGraphOnce(const std::vector<Landmark>& a, const std::vector<Landmark>& b, const SlideGraphParams& params);

}  // namespace slide::place
