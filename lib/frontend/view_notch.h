#pragma once
// Two objects standing side by side join in one cluster when the gap between them is narrower
// than the clustering cell, or when the rays into the gap hit their facing sides (two cars
// parked nose out, seen from the aisle). Seen from the sensor, such a cluster's nearest surface
// has a notch: over an interior stretch of azimuth its nearest return lies farther, by more
// than `depth`, than the nearest returns on both sides. One convex object (a car) has none:
// its nearest-range profile over azimuth falls to one minimum and rises from it.
// Points are in the sensor frame.
#include <optional>
#include <utility>
#include <vector>

#include "frontend/instance.h"

namespace slide::frontend {

struct NotchSplitParams {
  double bin_deg = 0.4;   // azimuth bins (wider than the LiDAR's azimuth step: every bin of a surface holds a return)
  double depth = 0.4;     // metres a notch lies beyond the nearest returns on both sides (0: off)
  double min_side = 0.5;  // metres of arc each side of the notch must span
  double band_low = 0.2;  // the profile is taken over points this far above the cluster's bottom ...
  double band_high = 1.0; // ... up to this far (a car's body, not its cabin)
};

// The two parts of `idx` (indices into `cloud`) on either side of its deepest notch in azimuth,
// or nothing when it has none.
std::optional<std::pair<std::vector<int>, std::vector<int>>> splitAtNotch(const Cloud& cloud, const std::vector<int>& idx,
                                                                          const NotchSplitParams& params);

}  // namespace slide::frontend
