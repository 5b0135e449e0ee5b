// slide-bag-to-folder: a LiDAR ROS 1 bag (or any recording the sensor driver reads) written as a
// KITTI-layout dataset folder (io/lidar_folder_writer.h), with the driver's bag options.
#include <spdlog/spdlog.h>

#include "app/app.h"
#include "bag_options.h"
#include "config/config.h"
#include "io/lidar_folder_writer.h"

int main(int argc, char** argv) {
  CLI::App app{"Write a LiDAR recording (e.g. a ROS 1 bag) as a KITTI-layout dataset folder", "slide-bag-to-folder"};
  slide::app::CommonOptions common;
  slide::app::addCommonOptions(app, common);
  std::string in, out, config_path;
  app.add_option("recording", in, "ROS 1 .bag file (or dataset folder)")->required();
  app.add_option("out", out, "Output folder (created; must be empty)")->required();
  app.add_option("--config", config_path, "YAML with a 'sensor_driver' section (bag, max_odom_gap), as the driver's");
  slide::io::DatasetOptions data_opt;
  slide::BagCli bag_cli;
  slide::addBagOptions(app, bag_cli);
  return slide::app::runApp(app, common, argc, argv, [&]() {
    if (bag_cli.list) return slide::listBag(in);
    if (!config_path.empty()) {
      const slide::ConfigNode root = slide::ConfigNode::load(config_path);
      if (root.has("sensor_driver")) {
        const slide::ConfigNode c = root.child("sensor_driver");
        slide::readBagConfig(c, bag_cli);
      }
    }
    data_opt.bag = bag_cli.options;
    data_opt.max_odometry_gap_s = bag_cli.max_odometry_gap_s;
    const slide::io::RobotDataset d = slide::io::openRobotDataset(in, data_opt);
    for (const std::string& w : d.warnings) spdlog::warn("{}: {}", d.path, w);
    if (d.dropped.total() > 0)
      spdlog::warn("{}: {} frames without an odometry pose left out ({} outside its time span, {} in gaps)", d.path,
                   d.dropped.total(), d.dropped.outside_span, d.dropped.gap);
    const slide::io::LidarFolderReport r = slide::io::writeLidarFolder(d, out);
    for (const std::string& e : r.unreadable) spdlog::warn("frame left out: {}", e);
    if (const std::string drops = d.reader->dropSummary(); !drops.empty()) spdlog::info("{}: {}", d.path, drops);
    spdlog::info("{}: {} frames written", out, r.written);
    return 0;
  });
}
