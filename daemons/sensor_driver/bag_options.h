#pragma once
// Command-line and config options of a recording shared by slide-sensor-driver and
// slide-bag-to-folder: ROS 1 bags (io/ros_bag_options.h), the odometry gap frames are dropped
// in, and --list: a bag's topics, types, counts and rates.
#include <CLI/CLI.hpp>

#include "config/config.h"
#include "io/robot_dataset.h"
#include "io/ros_bag_options.h"

namespace slide {

struct BagCli {
  io::BagOptions options;
  double max_odometry_gap_s = io::DatasetOptions{}.max_odometry_gap_s;  // io/robot_dataset.h
  bool list = false;
  std::vector<CLI::Option*> set;  // options given on the command line win over config
  CLI::Option* gap = nullptr;
};

void addBagOptions(CLI::App& app, BagCli& cli);
// Fills what the command line left unset from the sensor_driver section: max_odom_gap and
//   bag: {cloud_topic, color_topic, depth_topic, camera_info_topic, odom_topic, odom_frame,
//         body_frame, deskew, max_color_depth_dt, T_body_sensor: [x, y, z, qx, qy, qz, qw]}
void readBagConfig(const ConfigNode& sensor_driver, BagCli& cli);
// Prints the topics of `bag` to stdout; returns 0.
int listBag(const std::string& bag);

}  // namespace slide
