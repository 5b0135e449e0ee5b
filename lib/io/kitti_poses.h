#pragma once
// KITTI odometry files: poses (12 values of a 3x4 matrix per line, row-major) and times.
#include <string>
#include <vector>

#include "geometry/pose.h"

namespace slide::io {

std::vector<Pose> readKittiPoses(const std::string& path);
void writeKittiPoses(const std::string& path, const std::vector<Pose>& poses);
std::vector<double> readKittiTimes(const std::string& path);

// Velodyne-to-cam0 calibration Tr of KITTI odometry sequences 04-10.
Pose kittiVeloToCamTr0410();
// LiDAR poses in the first scan's LiDAR frame (x forward, y left, z up):
// inv(Tr) * P(i) * Tr for camera poses P(i).
std::vector<Pose> kittiLidarPoses(const std::vector<Pose>& cam_poses, const Pose& Tr);

}  // namespace slide::io
