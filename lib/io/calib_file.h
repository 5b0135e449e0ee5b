#pragma once
// KITTI-style calibration files: one "KEY: v1 v2 ..." line per entry.
// Simulator LiDAR datasets write "Tr:" (12 values, sensor-to-pose-frame, identity because
// poses.txt already holds LiDAR poses). RGBD datasets write
//   K: fx 0 cx 0 fy cy 0 0 1      size: width height      depth_scale: 0.001
//   T_body_camera: 12 values (3x4 row-major, optical frame to body frame)
#include <map>
#include <string>
#include <vector>

#include "geometry/pose.h"

namespace slide::io {

using CalibEntries = std::map<std::string, std::vector<double>>;

// Throws IoError naming the file and line for a missing file or an unparsable line.
CalibEntries readCalibFile(const std::string& path);
void writeCalibFile(const std::string& path, const CalibEntries& entries);

// Entry `key` with exactly n values; throws IoError naming file and key otherwise.
std::vector<double> calibValues(const CalibEntries& calib, const std::string& path, const std::string& key, int n);
// A 3x4 row-major transform entry (e.g. "Tr") as a pose.
Pose calibPose(const CalibEntries& calib, const std::string& path, const std::string& key);
std::vector<double> poseToCalib(const Pose& T);

}  // namespace slide::io
