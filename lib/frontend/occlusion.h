#pragma once
// Is a cluster seen whole? A LiDAR sees an object's full width only where the rays just past
// its edges go by it; where a nearer return lies right beyond an edge in azimuth, on the same
// beam, something in front hides the rest of it, and the cluster may be the visible part of a
// larger object (the end of a car parked behind another, the side of a wall behind a pole).
// Its extents are then lower bounds, and a classification by extent ("compact, so other")
// does not hold. Points are in the sensor frame.
#include <vector>

#include "frontend/scan_lines.h"

namespace slide::frontend {

struct OcclusionParams {
  double window_deg = 2.0;          // azimuth searched beyond an edge for the next return
  double beam_tolerance_deg = 0.1;  // elevation difference of returns on the same beam
  double min_gap = 0.5;             // metres (horizontal range) that return must be nearer
};

// Share of the beams through `points` (indices into the cloud `lines` indexes; `in_set` marks
// them, sized like the cloud) whose next return beyond either azimuth edge is nearer than
// the edge by min_gap. 0 for an empty set.
double occludedFraction(const Cloud& cloud, const ScanLines& lines, const std::vector<int>& points,
                        const std::vector<char>& in_set, const OcclusionParams& params);

}  // namespace slide::frontend
