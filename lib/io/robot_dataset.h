#pragma once
// One robot's recording as the sensor driver replays it: frame times, the odometry pose at
// each frame's time, and a reader for the frames. Layouts:
//
// LiDAR (KITTI layout):  velodyne/NNNNNN.bin, labels/NNNNNN.label (optional), times.txt
// RGBD (TUM layout):     associations.txt, rgb/, depth/, instances/ (optional), calib.txt
// Both:                  odom.txt (required: odometry, TUM trajectory in the robot's own
//                        odometry frame, at its own rate), groundtruth.txt (TUM, world frame,
//                        optional, at its own times), robot.yaml (simulator metadata, optional).
//                        poses.txt (KITTI ground truth) is never read as odometry.
// PCD folder:            *.pcd scans (PCL's format; sorted by name), times.txt (or times as
//                        file names), odom.txt (io/pcd_folder.h)
// ROS 1 bag:             a .bag file with the topics of DatasetOptions::bag (io/ros_bag.h)
//
// Odometry is interpolated at each frame's time (geometry/stamped_pose.h); frames before or
// after the odometry's span, or inside a gap longer than max_odometry_gap_s, are dropped and
// counted in `dropped`, never given a guessed pose.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geometry/stamped_pose.h"
#include "io/frame_reader.h"
#include "io/ros_bag_options.h"

namespace slide::io {

struct DatasetOptions {
  double max_odometry_gap_s = 0.5;  // odometry samples further apart than this give no pose between them
  BagOptions bag;                   // topics and frames when the source is a bag
};

// Frames dropped for want of an odometry pose.
struct OdometryDrops {
  std::size_t outside_span = 0;  // before the first or after the last odometry sample
  std::size_t gap = 0;           // between two samples more than max_odometry_gap_s apart
  std::size_t total() const { return outside_span + gap; }
};

struct RobotDataset {
  enum class Sensor { Lidar, Rgbd };
  std::string path;                       // folder or bag file
  Sensor sensor = Sensor::Lidar;
  std::vector<double> times;              // one per kept frame, seconds
  std::vector<std::size_t> frame_ids;     // the reader's id of each kept frame
  std::vector<StampedPose> odometry;      // one per kept frame, at its time: T_odom_body
  std::vector<StampedPose> ground_truth;  // optional, at its own times
  CameraCalib camera;                     // RGBD only
  OdometryDrops dropped;
  std::vector<std::string> warnings;      // read, but suspect (e.g. uncorrected lens distortion); each once
  std::shared_ptr<const FrameReader> reader;

  std::size_t size() const { return times.size(); }
  LabelledScan scan(std::size_t i) const { return reader->scan(frame_ids.at(i)); }
  RgbdImages rgbd(std::size_t i) const { return reader->rgbd(frame_ids.at(i)); }
};

// Pose of the body in the odometry frame at a time (PoseMiss::None when found).
using PoseAtTimeFn = std::function<PoseMiss(double t, Pose& T_odom_body)>;

// Fills d.times, d.frame_ids and d.odometry with the frames (times[k], id k) that have a pose
// and counts the others in d.dropped. Throws IoError naming d.path when no frame is left.
void keepFramesWithOdometry(RobotDataset& d, const std::vector<double>& times, const PoseAtTimeFn& pose_at);

// Opens and validates a recording: a .bag file, or a folder whose layout is detected. Checks
// that frame files exist and that times and frames agree in count. Throws IoError naming the
// file and problem (missing, count mismatch, unparsable line, no odometry).
RobotDataset openRobotDataset(const std::string& path, const DatasetOptions& options = {});

}  // namespace slide::io
