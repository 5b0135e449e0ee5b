#pragma once
// PCD folders: a folder of LiDAR scans in PCL's .pcd format (ASCII, binary or compressed;
// sorted by file name) with their times and the robot's odometry:
//   NNN.pcd      fields decoded as io/point_cloud2.h decodes PointCloud2 (x, y, z, intensity, ...)
//   times.txt    one time in seconds per scan; without it each file's name is its time
//                (seconds, or nanoseconds when above 1e15: 1700000000.100000.pcd, 1700000000100000000.pcd)
//   odom.txt     odometry, TUM trajectory at its own rate (required)
// Scans are read by io/pcd_file.h.
#include <string>

#include "io/robot_dataset.h"

namespace slide::io {

// True when `dir` holds .pcd files.
bool isPcdFolder(const std::string& dir);

// Throws IoError naming the file: unreadable .pcd, times that do not match, no odometry.
RobotDataset openPcdFolder(const std::string& dir, const DatasetOptions& options);

}  // namespace slide::io
