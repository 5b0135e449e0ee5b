#pragma once
// Command-line and config options of slide-sensor-driver for ROS 1 bags (io/ros_bag_options.h),
// and --list: a bag's topics, types, counts and rates.
#include <CLI/CLI.hpp>

#include "config/config.h"
#include "io/ros_bag_options.h"

namespace slide {

struct BagCli {
  BagOptions options;
  bool list = false;
  std::vector<CLI::Option*> set;  // options given on the command line win over config
};

void addBagOptions(CLI::App& app, BagCli& cli);
// Fills what the command line left unset from a 'bag' section:
//   bag: {cloud_topic, color_topic, depth_topic, camera_info_topic, odom_topic, odom_frame,
//         body_frame, deskew, max_color_depth_dt, T_body_sensor: [x, y, z, qx, qy, qz, qw]}
void readBagConfig(const ConfigNode& sensor_driver, BagCli& cli);
// Prints the topics of `bag` to stdout; returns 0.
int listBag(const std::string& bag);

}  // namespace slide
