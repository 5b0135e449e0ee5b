#pragma once
// Ground estimate on a 2-D grid: the second-lowest point of each cell, the minimum of those
// over a window of cells (a lower envelope under car roofs and walls), then ground grown from
// the cells on that envelope to neighbours within max_step (so that it follows slopes, which
// the envelope alone cuts into); cells it does not reach (objects) take the ground of the
// nearest ground cell. Cells seen through the ground (reflections) are left out of the
// envelope (under_tolerance). Points within `threshold` of the estimate are ground.
#include <vector>

#include "frontend/instance.h"

namespace slide::frontend {

struct GroundParams {
  double cell = 0.5;         // metres
  int window = 3;            // cells on each side of a cell in the minimum filter
  double threshold = 0.25;   // metres above the estimate still counted as ground
  double max_range = 100.0;  // points farther (horizontally) are left out (height NaN)
  int min_cell_points = 2;   // cells with fewer points do not define ground (stray returns)
  double max_step = 0.0;     // metres between neighbouring ground cells (0: envelope only) ...
  double max_rise = 0.45;    // ... and at most this above the envelope (its error on a 25 % slope: 0.375)
  // A cell whose line of sight from the sensor (at the origin) passes more than this many metres
  // below the ground estimated nearer along it was seen through the ground: a reflection, left
  // out of the estimate (0: off).
  double under_tolerance = 0.0;
};

// Where the ground itself was seen: the grid's cells whose own returns lie on the estimate.
class SeenGround {
 public:
  // The height (z) of the ground returns in the cell holding (x, y); NaN where the cell holds
  // none (no returns, or only objects' returns above the estimate).
  float at(double x, double y) const;

 private:
  friend std::vector<float> heightAboveGround(const Cloud&, const GroundParams&, SeenGround*);
  double min_x_ = 0, min_y_ = 0, inv_cell_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<float> z_;
};

// Height of every point above the local ground estimate; NaN for non-finite or out-of-range
// points. `seen` (optional) receives where the ground was seen.
std::vector<float> heightAboveGround(const Cloud& cloud, const GroundParams& params, SeenGround* seen = nullptr);

}  // namespace slide::frontend
