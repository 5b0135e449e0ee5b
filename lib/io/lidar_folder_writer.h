#pragma once
// A LiDAR recording that openRobotDataset reads (e.g. a ROS 1 bag) written as a KITTI-layout
// folder that it reads back the same (io/robot_dataset.h): velodyne/NNNNNN.bin with each frame's
// points in the body frame as the reader returns them (moved by T_body_sensor, deskewed when
// asked), times.txt and odom.txt (the odometry at each frame's time, microseconds), calib.txt
// (Tr identity: the points are already in the body frame).
#include <string>
#include <vector>

#include "io/robot_dataset.h"

namespace slide::io {

struct LidarFolderReport {
  std::size_t written = 0;
  std::vector<std::string> unreadable;  // one IoError message per frame left out
};

// Writes d's frames into `dir` (created; it must not hold files). A frame that cannot be read
// is left out and reported. Throws IoError naming `dir` for a non-empty folder, an RGBD
// dataset or a file that cannot be written, and when no frame could be read.
LidarFolderReport writeLidarFolder(const RobotDataset& d, const std::string& dir);

}  // namespace slide::io
