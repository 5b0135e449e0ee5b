#pragma once
// Trajectories from files of either standard format, for evaluation and plots.
// TUM: "t tx ty tz qx qy qz qw" (8 numbers a line); KITTI: 12 numbers of a 3x4 matrix a line,
// stamped by a KITTI times file when given, else by frame index (0, 1, 2, ...).
#include <string>
#include <vector>

#include "io/tum_trajectory.h"

namespace slide::eval {

enum class TrajectoryFormat { Auto, Tum, Kitti };

// "auto", "tum" or "kitti"; throws std::invalid_argument otherwise.
TrajectoryFormat parseTrajectoryFormat(const std::string& s);

// Auto looks at the number of values on the first data line (8: TUM, 12: KITTI).
// Throws IoError naming the file on a bad file, a times file of another length included.
std::vector<StampedPose> readTrajectory(const std::string& path, TrajectoryFormat format = TrajectoryFormat::Auto,
                                        const std::string& kitti_times_path = "");

struct TrajectoryReadOptions {
  TrajectoryFormat format = TrajectoryFormat::Auto;
  std::string kitti_times;   // KITTI times file; empty: frame index
  bool kitti_lidar = false;  // KITTI camera poses -> LiDAR frame (x forward, z up), 04-10 calibration
  Pose placement = Pose::Identity();  // applied last: placement * pose
};

std::vector<StampedPose> readTrajectory(const std::string& path, const TrajectoryReadOptions& opts);

}  // namespace slide::eval
