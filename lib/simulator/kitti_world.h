#pragma once
// KITTI worlds: the real LiDAR trajectory of a KITTI odometry sequence with its real pole map
// (poles and trunks as cylinders), the ground following the trajectory 1.73 m below the
// sensor, and procedurally added parked cars, building walls and bushes along the road.
#include <string>
#include <vector>

#include "simulator/world.h"

namespace slide::simulator {

// Reads a pole map CSV (header "x,y", then one pole per line); throws IoError naming the file.
std::vector<Eigen::Vector2d> readPoleMap(const std::string& path);

// lidar_poses: LiDAR poses in the first scan's frame (kittiLidarPoses()).
World makeKittiWorld(const std::vector<Pose>& lidar_poses, const std::string& pole_csv, uint64_t seed);

}  // namespace slide::simulator
