#include "driver_options.h"

#include "config/config.h"

namespace slide {

void addDriverOptions(CLI::App& app, DriverCli& cli) {
  ReplayOptions& opt = cli.replay;
  app.add_option("dataset", cli.dataset, "Dataset folder of one robot (e.g. OUT/robot0) or a ROS 1 .bag file")->required();
  app::addRobotBusOptions(app, cli.bus)->description("Robot id (stamped into headers; picks the default bus)");
  app.add_option("--config", cli.config_path,
                 "YAML with a 'sensor_driver' section (rate, start_frame, start_time, max_odom_gap, detections, "
                 "detection_config, channels: scan, rgbd, odom, status; bag: cloud_topic, color_topic, depth_topic, "
                 "camera_info_topic, odom_topic, odom_frame, body_frame, deskew, max_color_depth_dt, "
                 "T_body_sensor: [x, y, z, qx, qy, qz, qw]); command-line options win");
  cli.rate = app.add_option("--rate", opt.rate, "Real-time factor (1 = real time, 5 = 5x; 0 = as fast as possible)")
                 ->capture_default_str();
  cli.start_frame = app.add_option("--start-frame", opt.start_frame, "Skip the first K frames")->capture_default_str();
  cli.start_time = app.add_option("--start-time", opt.start_time, "Skip the first S seconds of data")->capture_default_str();
  addBagOptions(app, cli.bag);
  app.add_option("--frames", opt.max_frames, "Send at most N frames (0 = all)")->capture_default_str();
  app.add_option("--log", cli.log_path, "Also write the messages to this LCM log file");
  app.add_flag("--no-publish", cli.no_publish, "Do not publish on the bus (with --log: write the log only)");
  app.add_flag("--no-progress", cli.no_progress, "No progress bar");
  cli.detections_opt =
      app.add_option("--detections", cli.detections,
                     "Labels / masks published with the raw data: none (a real robot's input), emulated (the "
                     "detection emulator's output, made from the dataset's ground truth) or oracle (the ground truth "
                     "itself: upper-bound runs only)")
          ->check(CLI::IsMember({"none", "emulated", "oracle"}))
          ->capture_default_str();
  app.add_flag("--oracle-labels", cli.oracle_labels,
               "Publish the dataset's ground-truth labels / masks (same as --detections oracle)");
  cli.detection_config_opt =
      app.add_option("--detection-config", cli.detection_config, "Detection emulator parameters (YAML)")
          ->capture_default_str();
  cli.scan = app.add_option("--scan-channel", opt.scan_channel, "LiDAR scan channel")->capture_default_str();
  cli.rgbd = app.add_option("--rgbd-channel", opt.rgbd_channel, "RGBD frame channel")->capture_default_str();
  cli.odom = app.add_option("--odom-channel", opt.odom_channel, "Odometry channel")->capture_default_str();
  cli.status = app.add_option("--status-channel", opt.status_channel, "Stream status channel")->capture_default_str();
}

DetectionSource readDriverConfig(DriverCli& cli) {
  ReplayOptions& opt = cli.replay;
  opt.robot = cli.bus.robot;
  if (cli.no_publish && cli.log_path.empty())
    throw std::runtime_error("--no-publish needs --log FILE (nothing to do otherwise)");
  opt.progress = !cli.no_progress;
  if (!cli.config_path.empty()) {
    const ConfigNode root = ConfigNode::load(cli.config_path);
    if (root.has("sensor_driver")) {
      const ConfigNode c = root.child("sensor_driver");
      if (!cli.rate->count()) opt.rate = c.get<double>("rate", opt.rate);
      if (!cli.start_frame->count()) opt.start_frame = c.get<int>("start_frame", opt.start_frame);
      if (!cli.start_time->count()) opt.start_time = c.get<double>("start_time", opt.start_time);
      readBagConfig(c, cli.bag);
      if (!cli.detections_opt->count() && !cli.oracle_labels) cli.detections = c.get<std::string>("detections", cli.detections);
      if (!cli.detection_config_opt->count())
        cli.detection_config = c.get<std::string>("detection_config", cli.detection_config);
      opt.max_gap_s = c.get<double>("max_gap_s", opt.max_gap_s);
      if (!(opt.max_gap_s > 0 && opt.max_gap_s <= 3600)) c.fail("max_gap_s", "must be in (0, 3600] seconds");
      if (c.has("channels")) {
        const ConfigNode ch = c.child("channels");
        if (!cli.scan->count()) opt.scan_channel = ch.get<std::string>("scan", opt.scan_channel);
        if (!cli.rgbd->count()) opt.rgbd_channel = ch.get<std::string>("rgbd", opt.rgbd_channel);
        if (!cli.odom->count()) opt.odom_channel = ch.get<std::string>("odom", opt.odom_channel);
        if (!cli.status->count()) opt.status_channel = ch.get<std::string>("status", opt.status_channel);
        ch.known({"scan", "rgbd", "odom", "status"});  // read above unless the command line set them
      }
      c.known({"rate", "start_frame", "start_time", "max_odom_gap", "detections", "detection_config"});
      c.rejectUnknownKeys();  // only its section: other daemons' sections may share the file
    }
  }
  if (cli.oracle_labels && cli.detections_opt->count() && cli.detections != "oracle")
    throw std::runtime_error("--oracle-labels contradicts --detections " + cli.detections);
  if (cli.oracle_labels) cli.detections = "oracle";
  return parseDetectionSource(cli.detections);
}

io::DatasetOptions datasetOptions(const DriverCli& cli) {
  io::DatasetOptions d;
  d.bag = cli.bag.options;
  d.max_odometry_gap_s = cli.bag.max_odometry_gap_s;
  return d;
}

}  // namespace slide
