#pragma once
// SlideMatch: exhaustive search over x, y and yaw. Both maps are zero-centred; the translation
// region is where B's centre can lie with B still touching A's extent. Coarse stage: for each
// yaw of a grid (step chosen so that B's far landmarks move about one bin per step), every
// class-consistent landmark pair votes for the translation it implies, which scores every
// translation of the region at once (per-class lists, no pair of different classes is ever
// looked at). The search grows outward from the centre of the yaw range (0, +step, -step, ...;
// every translation of the region at each yaw) and the time budget is checked after each yaw
// and every 64 landmarks within one: it is anytime and returns the best so far. Fine stage: the best coarse cells
// are rescored exactly (class-consistent matches within the position and size thresholds,
// per-class bucket grid) on finer grids, then refined and verified like SlideGraph's result.
#include "place/verify.h"

namespace slide {

struct SlideMatchParams {
  double budget_ms = 5000;        // wall-time budget of the coarse search
  double coarse_bin = 1.2;        // metres, translation bin of the voting stage
  std::size_t max_coarse_bins = 4'000'000;  // bins of the voting grid; larger regions get coarser bins
  double min_yaw_step_deg = 0.5;  // bounds of the automatic yaw step
  double max_yaw_step_deg = 5.0;
  std::size_t refine_candidates = 12;  // coarse peaks rescored on the fine grid, verified best first
  std::size_t min_landmarks = 4;
  VerifyParams verify;
};

PlaceResult slideMatch(const std::vector<Landmark>& a, const std::vector<Landmark>& b, const SlideMatchParams& params);

}  // namespace slide
