// slide-sensor-driver: replays one robot's recording (simulator output, KITTI-style LiDAR or
// TUM-style RGBD folder, PCD folder, ROS 1 bag) onto the robot bus as SCAN / RGBD, ODOM and
// SENSOR_STATUS (FAILED, with the reason, when it stops on an error), and/or into an LCM log
// that lcm-logplayer replays. Ground-truth labels and masks stay on disk unless asked for
// (--detections oracle / --oracle-labels); --detections emulated publishes the detection
// emulator's output (config/detections.yaml) instead.
#include <spdlog/spdlog.h>

#include "app/app.h"
#include "app/stop_signal.h"
#include "driver_options.h"

using namespace slide;

int main(int argc, char** argv) {
  CLI::App app{"Replay a robot dataset onto the robot bus (and/or into an LCM log)", "slide-sensor-driver"};
  app::CommonOptions common;
  app::addCommonOptions(app, common);
  DriverCli cli;
  addDriverOptions(app, cli);
  return app::runApp(app, common, argc, argv, [&]() {
    if (cli.bag.list) return listBag(cli.dataset);
    std::unique_ptr<lcm::LCM> bus;
    std::unique_ptr<MessageSink> sink;
    StreamProgress progress;
    progress.source = cli.dataset;
    progress.detections = cli.oracle_labels ? "oracle" : cli.detections;
    const std::string url = cli.bus.resolve();
    try {
      const DetectionSource source = readDriverConfig(cli);
      const FramePerception perception = openPerception(source, cli.detection_config, cli.replay.robot);
      progress.detections = toString(source);
      const io::RobotDataset d = io::openRobotDataset(cli.dataset, datasetOptions(cli));
      if (!cli.no_publish) {
        auto b = std::make_unique<lcm::LCM>(url);
        if (!b->good()) throw std::runtime_error("cannot open LCM bus " + url);
        bus = std::move(b);
        spdlog::info("publishing on {}", url);
      }
      sink = std::make_unique<MessageSink>(msg::lcmPublisher(bus.get()), cli.log_path);
      app::installStopHandlers();
      replayDataset(d, cli.replay, perception, *sink, app::stopRequested, progress);
      if (source == DetectionSource::Oracle) spdlog::warn("ORACLE run: ground-truth labels / masks were published");
      return app::stopRequested() ? 130 : 0;
    } catch (const std::exception& e) {
      publishFailed(bus, sink, !cli.no_publish, url, cli.log_path, cli.replay, progress, e.what());
      throw;
    }
  });
}
