#pragma once
// What to read from a ROS 1 bag (io/ros_bag.h): topics, frames, extrinsics. Plain data, no
// ROS headers; filled from the sensor driver's config and command line.
#include <optional>
#include <string>

#include "geometry/pose.h"

namespace slide::io {

struct BagOptions {
  // LiDAR: a sensor_msgs/PointCloud2 topic. RGBD: sensor_msgs/Image colour (bgr8/rgb8) and
  // depth (16UC1 millimetres or 32FC1 metres) topics and a sensor_msgs/CameraInfo topic.
  // Exactly one of cloud_topic and (color_topic, depth_topic) is set.
  std::string cloud_topic, color_topic, depth_topic, camera_info_topic;
  // Odometry: a nav_msgs/Odometry topic, or (when empty) the /tf chain odom_frame -> body_frame.
  std::string odom_topic;
  std::string odom_frame = "odom";
  // The robot's body frame (x forward, y left, z up). Empty: the Odometry messages'
  // child_frame_id, or "base_link" for a /tf chain.
  std::string body_frame;
  // T_body_sensor of the cloud's or camera's frame; unset: looked up in /tf_static (and /tf).
  std::optional<Pose> T_body_sensor;
  bool deskew = false;             // motion-compensate each sweep from its per-point times
  double max_color_depth_dt = 0.02;  // seconds between a colour and a depth image of one frame
};

}  // namespace slide::io
