#pragma once
// SlideMatch: exhaustive search over x, y and yaw. Both maps are zero-centred; the translation
// region is where B's centre can lie with B still touching A's extent. Coarse stage: for each
// yaw of a grid (step chosen so that B's far landmarks move about one bin per step), every
// class-consistent landmark pair votes for the translation it implies, which scores every
// translation of the region at once (per-class lists, no pair of different classes is ever
// looked at). The search grows outward from the centre of the yaw range (0, +step, -step, ...;
// every translation of the region at each yaw) and the budget (the querying thread's CPU time) is checked after each yaw
// and every 64 landmarks within one: it is anytime and returns the best so far. Fine stage: the best coarse cells
// are rescored exactly (class-consistent matches within the position and size thresholds,
// per-class bucket grid) on finer grids, then refined and verified like SlideGraph's result.
//
// Large maps (the exhaustive vote would cast more than exhaustive_max_votes votes): the coarse
// stage is pruned by neighbourhoods (place/neighbourhood.h). Each landmark of B is paired only
// with the pruned_candidates landmarks of A of its class whose neighbourhood descriptors are
// nearest; each such pair whose neighbourhoods agree on a yaw (min_local_votes neighbour pairs,
// significantly more than chance) votes, weighted by its votes above chance, at that yaw, for where the centre of B's tile holding it (tile metres square) lands
// in A. A tile is small enough that a few degrees of yaw error move its centre by less than a
// vote bin, so the votes of one true overlap gather whatever the maps' extents; the strongest
// cells go to the same fine stage, rescored over the landmarks of B near their tile. B's
// landmarks are visited in a fixed shuffled order and the budget is checked every 64 of them:
// a query out of time still decides on the votes of a sample of the whole map.
//
// Smaller maps (tile_votes): the pruned stage runs after the exhaustive one as well and its
// peaks join the fine stage. A 2.4 m box of the exhaustive vote collects a few chance votes
// wherever B lies over A, so the strongest exhaustive peaks are where most of B lies over A; a
// true overlap along a fifth of B's route, bent by drift, does not reach them (the place bench's
// realistic forest: 5 of 10 such pairs found, 8 with the tile votes; none lost anywhere).
#include "place/verify.h"

namespace slide::place {

struct SlideMatchParams {
  double budget_ms = 5000;        // thread CPU time budget of the coarse search
  double coarse_bin = 1.2;        // metres, translation bin of the voting stage
  std::size_t max_coarse_bins = 4'000'000;  // bins of the voting grid; larger regions get coarser bins
  double min_yaw_step_deg = 0.5;  // bounds of the automatic yaw step
  double max_yaw_step_deg = 5.0;
  std::size_t refine_candidates = 12;  // coarse peaks rescored on the fine grid, verified best first
  std::size_t min_landmarks = 4;
  // Pruned coarse stage for large maps.
  double exhaustive_max_votes = 2e9;     // same-class pairs x yaws above this: pruned search
  double neighbourhood_radius = 12.0;    // metres
  std::size_t pruned_candidates = 24;    // A landmarks per B landmark, nearest by descriptor
  int min_local_votes = 4;               // neighbour pairs agreeing on the yaw of one landmark pair...
  double local_significance = 3.0;       // ...and at least chance + this x sqrt(chance) of them
  double local_yaw_bin_deg = 3.0;        // yaw bin of the local and the global vote
  double tile = 60.0;                    // metres, side of B's tiles
  double vote_bin = 3.0;                 // metres, bin of where a tile's centre lands in A
  bool tile_votes = true;                // smaller maps: the pruned stage's peaks join the exhaustive ones
  VerifyParams verify;
};

// trials (optional): every refined candidate as verified (accepted or not), strongest coarse peak
// first; the exhaustive search's view of the other alignments the maps allow (see recognizePlace).
PlaceResult slideMatch(const std::vector<Landmark>& a, const std::vector<Landmark>& b, const SlideMatchParams& params,
                       std::vector<PlaceResult>* trials = nullptr);

}  // namespace slide::place
