#pragma once
// Ground estimate on a 2-D grid: the lowest point of each cell, then the minimum over a
// window of cells (so that car roofs and walls, whose cells hold no ground, take the ground
// height of their surroundings). Points within `threshold` of that estimate are ground.
#include <vector>

#include "frontend/instance.h"

namespace slide {

struct GroundParams {
  double cell = 0.5;         // metres
  int window = 3;            // cells on each side of a cell in the minimum filter
  double threshold = 0.25;   // metres above the estimate still counted as ground
  double max_range = 100.0;  // points farther (horizontally) are left out (height NaN)
  int min_cell_points = 2;   // cells with fewer points do not define ground (stray returns)
};

// Height of every point above the local ground estimate; NaN for non-finite or out-of-range
// points.
std::vector<float> heightAboveGround(const Cloud& cloud, const GroundParams& params);

}  // namespace slide
