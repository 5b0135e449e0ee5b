#pragma once
// What a place-recognition query returns: the transform T_a_b (maps points of map B's frame
// into map A's frame) or "no transform" with the reason, plus the evidence.
#include <string>
#include <utility>
#include <vector>

#include "clock/thread_cpu.h"
#include "geometry/pose.h"

namespace slide::place {

enum class PlaceMethod { SlideGraph, SlideMatch };
const char* methodName(PlaceMethod m);

// A landmark of map A matched to a landmark of map B (indices into the Landmark vectors).
struct LandmarkMatch {
  std::size_t a = 0;
  std::size_t b = 0;
};

struct PlaceResult {
  bool found = false;
  std::string reason;          // why no transform (empty when found)
  Pose T_a_b = Pose::Identity();
  std::vector<LandmarkMatch> inliers;
  double residual_rms = 0;     // metres, over the inliers after refinement
  double support = 0;          // the inliers weighted by how well each fits: sum of 1 - (d / match radius)^2,
                               // d its horizontal residual (verify.h, strengthOf)
  double score = 0;            // method-specific: SlideMatch grid score, SlideGraph clique size
  double chance_inliers = 0;   // inliers expected by chance at this overlap (acceptance test)
  std::size_t covered = 0;     // B's landmarks that land where A has landmarks (acceptance test)
  double ms = 0;               // wall time of the query
  double cpu_ms = 0;           // CPU time of the calling thread during the query
  std::vector<std::pair<std::string, double>> stage_cpu_ms;  // CPU ms per stage, in order
  std::size_t associations = 0;       // SlideGraph: initial associations given to CLIPPER
  std::size_t clipper_edges = 0;      // SlideGraph: consistent pairs in the sparse graph
  std::size_t clipper_peak_bytes = 0; // SlideGraph: peak bytes held by the consistency graph
  bool budget_exhausted = false;      // stopped on its CPU-time budget (SlideGraph: no transform; SlideMatch: best so far)
  bool by_shape = false;              // matched by shape family: the maps' classes barely overlap
  bool by_tile_votes = false;         // SlideGraph found nothing; SlideMatch's tile votes did (place_config.h)
  // Verified, but another alignment explains the maps nearly as well (verify.h, the rival
  // test): no transform; T_a_b and inliers are the stronger hypothesis's.
  bool ambiguous = false;
};

}  // namespace slide::place
