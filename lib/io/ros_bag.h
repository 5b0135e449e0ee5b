#pragma once
// ROS 1 bags as robot recordings, read through rosbag_storage (rosbag::Bag, rosbag::View; no
// ROS master, no catkin). Topics, frames and extrinsics come from BagOptions
// (io/ros_bag_options.h). Messages are decoded from their serialized bytes with every length
// checked, so a corrupt message gives an IoError naming the bag, topic and message index.
#include <string>
#include <vector>

#include "io/robot_dataset.h"

namespace slide::io {

struct BagTopicInfo {
  std::string topic, type;
  std::size_t messages = 0;
  double first_s = 0, last_s = 0;  // record times
  double rateHz() const { return messages > 1 && last_s > first_s ? (messages - 1) / (last_s - first_s) : 0.0; }
};

// The bag's topics, sorted by name. Throws IoError for a missing, truncated or unindexed bag.
std::vector<BagTopicInfo> listBagTopics(const std::string& path);

// LiDAR (options.bag.cloud_topic) or RGBD (color_topic + depth_topic + camera_info_topic)
// frames with odometry from options.bag.odom_topic or the /tf chain odom_frame -> body_frame.
// Throws IoError naming the bag and topic (missing topic, wrong type, no odometry, no
// extrinsic) or message index (corrupt message, unsupported encoding).
RobotDataset openBagDataset(const std::string& path, const DatasetOptions& options);

}  // namespace slide::io
