#pragma once
// One robot's recorded (or simulated) dataset folder, as the sensor driver replays it.
//
// LiDAR (KITTI layout):  velodyne/NNNNNN.bin, labels/NNNNNN.label (optional), times.txt,
//                        poses.txt (ground-truth LiDAR poses, KITTI 3x4), calib.txt (Tr)
// RGBD (TUM layout):     associations.txt, rgb/, depth/, instances/ (optional), calib.txt
// Both:                  odom.txt (odometry, TUM trajectory, one line per frame, in the
//                        robot's own odometry frame), groundtruth.txt (TUM, world frame,
//                        optional), robot.yaml (simulator metadata, optional).
// For real KITTI folders without odom.txt, poses.txt (turned into LiDAR poses with calib.txt
// Tr: inv(Tr) * P * Tr) stands in for odometry.
#include <string>
#include <vector>

#include "io/rgbd_files.h"
#include "io/tum_trajectory.h"

namespace slide {

struct RobotDataset {
  enum class Sensor { Lidar, Rgbd };
  std::string dir;
  Sensor sensor = Sensor::Lidar;
  std::vector<double> times;              // one per frame, seconds
  std::vector<std::string> scans;         // LiDAR: absolute paths of velodyne/*.bin
  std::vector<Association> frames;        // RGBD: paths relative to dir
  CameraCalib camera;                     // RGBD only
  std::vector<StampedPose> odometry;      // one per frame (empty when the folder has none)
  std::vector<StampedPose> ground_truth;  // optional
  std::size_t size() const { return times.size(); }
};

// Opens and validates a dataset folder: detects its layout, checks that frame files exist
// and that times, odometry and frames agree in count. Throws IoError naming the file and
// problem (missing, count mismatch, unparsable line).
RobotDataset openRobotDataset(const std::string& dir);

}  // namespace slide
