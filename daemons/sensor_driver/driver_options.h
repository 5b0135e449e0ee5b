#pragma once
// The sensor driver's settings: its command line, and the sensor_driver section of a config
// file (--config), which fills what the command line left unset.
#include <CLI/CLI.hpp>
#include <string>

#include "app/robot_bus.h"
#include "bag_options.h"
#include "perception.h"
#include "sensor_driver_node.h"

namespace slide {

struct DriverCli {
  std::string dataset, log_path, config_path;
  app::RobotBusOptions bus;
  ReplayOptions replay;
  BagCli bag;
  bool no_publish = false, no_progress = false, oracle_labels = false;
  std::string detections = "none";
  std::string detection_config = std::string(SLIDE_SOURCE_DIR) + "/config/detections.yaml";
  // Given on the command line (these win over the config).
  CLI::Option *rate = nullptr, *start_frame = nullptr, *start_time = nullptr, *detections_opt = nullptr,
              *detection_config_opt = nullptr, *scan = nullptr, *rgbd = nullptr, *odom = nullptr, *status = nullptr;
};

void addDriverOptions(CLI::App& app, DriverCli& cli);

// Reads the config's sensor_driver section (rate, start_frame, start_time, max_gap_s,
// max_odom_gap, detections, detection_config, channels, bag) into what the command line left
// unset, checks the combination, and returns the detection source. Throws on a bad setting.
DetectionSource readDriverConfig(DriverCli& cli);

// The dataset reader's options.
io::DatasetOptions datasetOptions(const DriverCli& cli);

}  // namespace slide
