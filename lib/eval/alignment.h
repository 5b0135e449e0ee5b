#pragma once
// Rigid alignment of corresponding point sets, as trajectory evaluation needs it:
// Umeyama's closed form (SE(3) or Sim(3)) and a yaw-only (x, y, z, yaw) variant.
#include <string>
#include <vector>

#include "geometry/pose.h"

namespace slide::eval {

enum class TrajectoryAlignment { None, Se3, Sim3, Yaw4Dof };

// "none", "se3", "sim3" or "yaw" (x, y, z, yaw); throws std::invalid_argument otherwise.
TrajectoryAlignment parseAlignment(const std::string& name);
const char* alignmentName(TrajectoryAlignment a);

struct AlignmentResult {
  Pose T = Pose::Identity();  // maps estimate points into the reference frame
  double scale = 1.0;         // Sim3 only
};

// Best transform (and scale) with ref[i] ≈ s * R * est[i] + t in the least-squares sense.
// Needs at least 3 non-collinear points for Se3/Sim3, 2 for Yaw4Dof (None: identity).
AlignmentResult align(const std::vector<Eigen::Vector3d>& est, const std::vector<Eigen::Vector3d>& ref,
                      TrajectoryAlignment mode);

}  // namespace slide::eval
