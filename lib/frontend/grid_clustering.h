#pragma once
// Euclidean-style clustering on a voxel grid: points whose cells touch (26-neighbourhood in
// 3-D, 8 in 2-D) belong to one cluster. Linear in the number of points apart from one sort.
#include <vector>

#include "frontend/instance.h"

namespace slide::frontend {

struct GridClusterParams {
  double cell = 0.3;      // cell edge in metres; gaps wider than ~2 cells always split
  bool planar = false;    // cluster on x, y only
  int min_points = 10;
  int max_points = 1 << 30;
};

// Clusters of `subset` (indices into `cloud`; all points when empty), largest first.
std::vector<std::vector<int>> clusterGrid(const Cloud& cloud, const std::vector<int>& subset,
                                          const GridClusterParams& params);

}  // namespace slide::frontend
