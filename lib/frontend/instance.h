#pragma once
// What the segmenter hands to the tracker: per-frame object instances (class, points in the
// sensor frame) and the odometry pose the frame was taken at.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "geometry/pose.h"

namespace slide::frontend {

using Cloud = std::vector<Eigen::Vector3f>;

struct Instance {
  int id = 0;              // instance id within its frame (1, 2, ...)
  int class_id = 0;        // key into the ClassTable
  float confidence = 1.0f;
  Cloud points;            // sensor frame
  // Sensor frame: centres of cells near the object the sensor saw through (FreeSpace): no part
  // of it stands there. Empty when not known.
  Cloud free_space;
};

struct FrameInstances {
  std::int64_t utime = 0;
  Pose odom_pose = Pose::Identity();  // T_odom_body at the frame's time
  std::vector<Instance> instances;
};

// Points of `cloud` mapped by T (T * p), in float.
Cloud transformCloud(const Pose& T, const Cloud& cloud);
// Mean of the points; zero for an empty cloud.
Eigen::Vector3d centroidOf(const Cloud& cloud);

}  // namespace slide::frontend
