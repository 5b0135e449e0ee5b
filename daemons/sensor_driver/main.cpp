// slide-sensor-driver: replays one robot's recording (simulator output, KITTI-style LiDAR or
// TUM-style RGBD folder, PCD folder, ROS 1 bag) onto the robot bus as SCAN / RGBD, ODOM and
// SENSOR_STATUS (FAILED, with the reason, when it stops on an error), and/or into an LCM log
// that lcm-logplayer replays. Ground-truth labels and masks stay on disk unless asked for
// (--detections oracle / --oracle-labels); --detections emulated publishes the detection
// emulator's output (config/detections.yaml) instead.
#include <spdlog/spdlog.h>

#include <atomic>
#include <csignal>

#include "app/app.h"
#include "config/config.h"
#include "bag_options.h"
#include "perception.h"
#include "replay.h"
#include "slide/stream_status_t.hpp"

namespace {
std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }

// Before the driver exits on an error: FAILED with the reason on the status channel (bus and
// log), opening the bus or the log first when the error came before them. Never throws; the
// error itself is reported by the caller.
void publishFailed(std::unique_ptr<lcm::LCM>& bus, std::unique_ptr<slide::MessageSink>& sink, bool publish,
                   const std::string& url, const std::string& log_path, const slide::ReplayOptions& opt,
                   const slide::StreamProgress& progress, const std::string& reason) {
  try {
    if (!sink) {
      if (publish && !bus) {
        auto b = std::make_unique<lcm::LCM>(url);
        if (b->good()) bus = std::move(b);
      }
      try {
          sink = std::make_unique<slide::MessageSink>(bus.get(), log_path);
        } catch (const std::exception&) {  // the log is what failed: the bus alone
          sink = std::make_unique<slide::MessageSink>(bus.get(), "");
        }
      }
      slide::sendStatus(*sink, opt, progress, slide::stream_status_t::FAILED, reason);
    } catch (const std::exception& e) {
      spdlog::warn("could not publish the FAILED status on {}: {}", opt.status_channel, e.what());
    }
  }
  }  // namespace

  int main(int argc, char** argv) {
    CLI::App app{"Replay a robot dataset onto the robot bus (and/or into an LCM log)", "slide-sensor-driver"};
    slide::CommonOptions common;
    slide::addCommonOptions(app, common);
    slide::ReplayOptions opt;
    std::string dataset, lcm_url, log_path, config_path;
    bool no_publish = false, no_progress = false, oracle_labels = false;
    std::string detections = "none", detection_config = std::string(SLIDE_SOURCE_DIR) + "/config/detections.yaml";
    app.add_option("dataset", dataset, "Dataset folder of one robot (e.g. OUT/robot0) or a ROS 1 .bag file")->required();
    app.add_option("--robot", opt.robot, "Robot id (stamped into headers; picks the default bus)")->capture_default_str();
    app.add_option("--lcm-url", lcm_url, "Robot bus URL (default udpm://239.255.76.67:<7667+robot>?ttl=0&recv_buf_size=4194304)");
    app.add_option("--config", config_path,
                   "YAML with a 'sensor_driver' section (rate, start_frame, start_time, max_odom_gap, detections, "
                   "detection_config, channels: scan, rgbd, odom, status; bag: cloud_topic, color_topic, depth_topic, "
                   "camera_info_topic, odom_topic, odom_frame, body_frame, deskew, max_color_depth_dt, "
                   "T_body_sensor: [x, y, z, qx, qy, qz, qw]); command-line options win");
    auto* rate_opt = app.add_option("--rate", opt.rate, "Real-time factor (1 = real time, 5 = 5x; 0 = as fast as possible)")
        ->capture_default_str();
    auto* start_frame_opt = app.add_option("--start-frame", opt.start_frame, "Skip the first K frames")->capture_default_str();
    auto* start_time_opt = app.add_option("--start-time", opt.start_time, "Skip the first S seconds of data")->capture_default_str();
    slide::DatasetOptions data_opt;
    slide::BagCli bag_cli;
    slide::addBagOptions(app, bag_cli);
    app.add_option("--frames", opt.max_frames, "Send at most N frames (0 = all)")->capture_default_str();
    app.add_option("--log", log_path, "Also write the messages to this LCM log file");
    app.add_flag("--no-publish", no_publish, "Do not publish on the bus (with --log: write the log only)");
    app.add_flag("--no-progress", no_progress, "No progress bar");
    auto* detections_opt =
        app.add_option("--detections", detections,
                       "Labels / masks published with the raw data: none (a real robot's input), emulated (the "
                       "detection emulator's output, made from the dataset's ground truth) or oracle (the ground truth "
                       "itself: upper-bound runs only)")
            ->check(CLI::IsMember({"none", "emulated", "oracle"}))
            ->capture_default_str();
    app.add_flag("--oracle-labels", oracle_labels,
                 "Publish the dataset's ground-truth labels / masks (same as --detections oracle)");
    auto* detection_config_opt =
        app.add_option("--detection-config", detection_config, "Detection emulator parameters (YAML)")->capture_default_str();
    auto* scan_opt = app.add_option("--scan-channel", opt.scan_channel, "LiDAR scan channel")->capture_default_str();
    auto* rgbd_opt = app.add_option("--rgbd-channel", opt.rgbd_channel, "RGBD frame channel")->capture_default_str();
    auto* odom_opt = app.add_option("--odom-channel", opt.odom_channel, "Odometry channel")->capture_default_str();
    auto* status_opt = app.add_option("--status-channel", opt.status_channel, "Stream status channel")->capture_default_str();

    return slide::runApp(app, common, argc, argv, [&]() {
      if (bag_cli.list) return slide::listBag(dataset);
      std::unique_ptr<lcm::LCM> bus;
      std::unique_ptr<slide::MessageSink> sink;
      slide::StreamProgress progress;
      progress.source = dataset;
      progress.detections = oracle_labels ? "oracle" : detections;
      const std::string url = lcm_url.empty() ? slide::robotBusUrl(opt.robot) : lcm_url;
      try {
      if (no_publish && log_path.empty()) throw std::runtime_error("--no-publish needs --log FILE (nothing to do otherwise)");
      opt.progress = !no_progress;
      if (!config_path.empty()) {
        const slide::ConfigNode root = slide::ConfigNode::load(config_path);
        if (root.has("sensor_driver")) {
          const slide::ConfigNode c = root.child("sensor_driver");
          if (!rate_opt->count()) opt.rate = c.get<double>("rate", opt.rate);
          if (!start_frame_opt->count()) opt.start_frame = c.get<int>("start_frame", opt.start_frame);
          if (!start_time_opt->count()) opt.start_time = c.get<double>("start_time", opt.start_time);
          slide::readBagConfig(c, bag_cli);
          if (!detections_opt->count() && !oracle_labels) detections = c.get<std::string>("detections", detections);
          if (!detection_config_opt->count()) detection_config = c.get<std::string>("detection_config", detection_config);
          opt.max_gap_s = c.get<double>("max_gap_s", opt.max_gap_s);
          if (!(opt.max_gap_s > 0 && opt.max_gap_s <= 3600)) c.fail("max_gap_s", "must be in (0, 3600] seconds");
          if (c.has("channels")) {
            const slide::ConfigNode ch = c.child("channels");
            if (!scan_opt->count()) opt.scan_channel = ch.get<std::string>("scan", opt.scan_channel);
            if (!rgbd_opt->count()) opt.rgbd_channel = ch.get<std::string>("rgbd", opt.rgbd_channel);
            if (!odom_opt->count()) opt.odom_channel = ch.get<std::string>("odom", opt.odom_channel);
            if (!status_opt->count()) opt.status_channel = ch.get<std::string>("status", opt.status_channel);
            ch.known({"scan", "rgbd", "odom", "status"});  // read above unless the command line set them
          }
          c.known({"rate", "start_frame", "start_time", "max_odom_gap", "detections", "detection_config"});
          c.rejectUnknownKeys();  // only its section: other daemons' sections may share the file
        }
      }
      if (oracle_labels && detections_opt->count() && detections != "oracle")
        throw std::runtime_error("--oracle-labels contradicts --detections " + detections);
      if (oracle_labels) detections = "oracle";
      const slide::DetectionSource source = slide::parseDetectionSource(detections);
      slide::DetectionEmulatorConfig emulator;
      if (source == slide::DetectionSource::Emulated) emulator = slide::loadDetectionEmulatorConfig(detection_config);
      const slide::FramePerception perception(source, emulator, opt.robot);
      if (source == slide::DetectionSource::Oracle)
        spdlog::warn("ORACLE: publishing the dataset's GROUND-TRUTH labels / masks (--detections oracle); a real robot "
                     "has none, so every figure from this run is an upper bound");
      else if (source == slide::DetectionSource::Emulated)
        spdlog::info("detections: emulated from ground truth inside the driver ({}, seed {}); no ground truth is published",
                     detection_config, emulator.seed);
      else
        spdlog::info("detections: none (raw data only; ground-truth labels / masks stay on disk)");
      progress.detections = slide::toString(source);
      data_opt.bag = bag_cli.options;
      data_opt.max_odometry_gap_s = bag_cli.max_odometry_gap_s;
      const slide::RobotDataset d = slide::openRobotDataset(dataset, data_opt);
      if (!no_publish) {
        auto b = std::make_unique<lcm::LCM>(url);
        if (!b->good()) throw std::runtime_error("cannot open LCM bus " + url);
        bus = std::move(b);
        spdlog::info("publishing on {}", url);
      }
      sink = std::make_unique<slide::MessageSink>(bus.get(), log_path);
      std::signal(SIGINT, onSignal);
      std::signal(SIGTERM, onSignal);
      slide::replayDataset(d, opt, perception, *sink, [] { return g_stop.load(); }, progress);
      if (source == slide::DetectionSource::Oracle) spdlog::warn("ORACLE run: ground-truth labels / masks were published");
      return g_stop ? 130 : 0;
    } catch (const std::exception& e) {
      publishFailed(bus, sink, !no_publish, url, log_path, opt, progress, e.what());
      throw;
    }
  });
}
