#pragma once
// The geometric front-end's own steps against PCL's standard ones on real data, same input:
//  - ground: our grid estimate vs one RANSAC plane (SACMODEL_PLANE) on a SemanticKITTI scan,
//    scored with the scan's labels (ground classes kept as ground, object points kept off it);
//  - clustering: our voxel-grid union-find vs EuclideanClusterExtraction (k-d tree) on the
//    scan's above-ground points (counts and time; the connectivity rules differ, see .cpp);
//  - circles: our RANSAC + algebraic refit vs SACMODEL_CIRCLE2D on the TLS breast-height slice.
// PCL's headers stay inside pcl_reference.cpp.
#include <string>

#include "frontend/frontend_config.h"

namespace slide {

struct PclComparison {
  // Ground, over the labelled points within the segmenter's range.
  double ours_ground_kept = 0, pcl_ground_kept = 0;      // labelled ground points called ground
  double ours_object_lost = 0, pcl_object_lost = 0;      // labelled car/trunk/pole points called ground
  double ours_ground_ms = 0, pcl_ground_ms = 0;
  // Clustering of the above-ground points.
  int ours_clusters = 0, pcl_clusters = 0;
  double ours_cluster_ms = 0, pcl_cluster_ms = 0;
  // Circle on the TLS slice.
  double ours_radius = 0, pcl_radius = 0, ours_circle_ms = 0, pcl_circle_ms = 0;
};

// Medians over `runs` timings (thread CPU time). Throws IoError for missing files.
PclComparison comparePcl(const std::string& kitti_bin, const std::string& tls_slice,
                         const frontend::FrontendConfig& cfg, int runs);

}  // namespace slide
