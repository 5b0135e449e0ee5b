#pragma once
// Is a cluster two things, one standing on the other (a monitor on a table)? Each beam of a
// spinning LiDAR crosses the cluster as one arc at one height; the arc's width across the line
// of sight, from the bottom up, is the cluster's outline as seen. A single piece of furniture
// widens and narrows once. Something standing on a table narrows where the two meet (the
// table top falls away towards its edge, the monitor's foot is small) and widens again above:
// a neck. A column seen through foliage or with dropouts shows single short arcs instead:
// arcs of few returns are left out, and a neck must narrow over the arcs beside it too.
// Points are in the sensor frame (sensor at the origin, z up).
#include <optional>
#include <utility>
#include <vector>

#include "frontend/instance.h"

namespace slide::frontend {

struct StackedSplitParams {
  double max_neck_ratio = 0.0;      // a neck's arc is at most this share of the widest below and above it (0: off) ...
  double max_side_ratio = 0.9;      // ... the arcs just below and above it at most this share of the widest on their side ...
  double min_neck_depth = 0.1;      // ... and it is at least this much (metres) narrower than both
  int min_arc_points = 8;           // arcs of fewer returns say nothing of the outline
  double beam_tolerance_deg = 0.1;  // returns within this elevation of each other lie on one beam
  int min_points = 60;              // each part holds at least this many points ...
  double min_height = 0.15;         // ... and stands at least this tall (metres)
  double min_neck_height = 0.3;     // the neck stands at least this high above the ground (metres)
};

// The parts below and above the narrowest neck of `cluster` (indices into `cloud`; `h` the
// heights above ground, sized like the cloud), or nullopt when it has none.
std::optional<std::pair<std::vector<int>, std::vector<int>>> splitAtNeck(const Cloud& cloud, const std::vector<float>& h,
                                                                         const std::vector<int>& cluster,
                                                                         const StackedSplitParams& params);

}  // namespace slide::frontend
