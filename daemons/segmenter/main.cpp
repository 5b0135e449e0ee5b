// slide-segmenter: SCAN (slide.lidar_scan_t) and RGBD (slide.rgbd_frame_t) in, per-frame
// object instances with the odometry pose of the frame (slide.frame_instances_t) out on
// INSTANCES, and a thinned copy of two a second on INSTANCES_PREVIEW (for the viewer and the run
// logs). Frames wait for the ODOM messages around their time.
#include <spdlog/spdlog.h>

#include <lcm/lcm-cpp.hpp>

#include "app/app.h"
#include "app/channels.h"
#include "app/clock.h"
#include "app/robot_bus.h"
#include "app/stop_signal.h"
#include "msg/inbox.h"
#include "msg/status_beacon.h"
#include "segmenter_node.h"

using namespace slide;

int main(int argc, char** argv) {
  CLI::App app{"Segmenter daemon: LiDAR scans (labelled, geometric or learned mode) and RGBD frames (instance masks) "
               "to per-frame object instances stamped with their odometry pose"};
  app::CommonOptions common;
  app::addCommonOptions(app, common);
  app::RobotBusOptions bus;
  std::string config_file = std::string(SLIDE_SOURCE_DIR) + "/config/frontend.yaml";
  std::string classes_file = std::string(SLIDE_SOURCE_DIR) + "/config/classes.yaml";
  std::string scan_ch = app::channels::kScan, rgbd_ch = app::channels::kRgbd, odom_ch = app::channels::kOdom;
  std::string out_ch = app::channels::kInstances, status_ch = app::channels::kDaemonStatus, mode;
  std::size_t max_pending = 50;
  app::addRobotBusOptions(app, bus);
  app.add_option("--config", config_file, "Front-end YAML")->capture_default_str();
  app.add_option("--classes", classes_file, "Class table YAML")->capture_default_str();
  app.add_option("--mode", mode, "LiDAR mode, overrides the config: auto | labelled | geometric | learned")
      ->check(CLI::IsMember({"auto", "labelled", "geometric", "learned"}));
  app.add_option("--scan-channel", scan_ch, "LiDAR scans in")->capture_default_str();
  app.add_option("--rgbd-channel", rgbd_ch, "RGBD frames in")->capture_default_str();
  app.add_option("--odom-channel", odom_ch, "Odometry in")->capture_default_str();
  app.add_option("--instances-channel", out_ch, "Instances out")->capture_default_str();
  SegmenterNode::Preview preview{app::channels::kInstancesPreview};
  app.add_option("--preview-channel", preview.channel, "Thinned copy of the instances out, for the viewer ('': none)")
      ->capture_default_str();
  app.add_option("--preview-period", preview.period_s, "Seconds of frame time between two previews")->capture_default_str();
  app.add_option("--preview-points", preview.max_points, "Points of a preview (thinned)")->capture_default_str();
  app.add_option("--status-channel", status_ch, "Counts out (daemon_status_t every 5 s)")->capture_default_str();
  app.add_option("--max-pending", max_pending, "Frames kept waiting for odometry")->capture_default_str();
  return app::runApp(app, common, argc, argv, [&]() {
    const int robot = bus.robot;
    const std::string url = bus.resolve();
    const ClassTable classes = ClassTable::load(classes_file);
    frontend::FrontendConfig cfg = frontend::loadFrontendConfig(config_file);
    if (!mode.empty()) cfg.lidar_mode = mode;
    lcm::LCM lcm(url);
    if (!lcm.good()) throw std::runtime_error("cannot open LCM at " + url);
    SegmenterNode node(robot, out_ch, classes, cfg, max_pending, msg::lcmPublisher(lcm));
    node.setPreview(preview);
    msg::Inbox inbox(lcm);
    inbox.subscribe<lidar_scan_t>(scan_ch, [&](auto&, auto& m) { node.onScan(m); });
    inbox.subscribe<rgbd_frame_t>(rgbd_ch, [&](auto&, auto& m) { node.onRgbd(m); });
    inbox.subscribe<odometry_t>(odom_ch, [&](auto&, auto& m) { node.onOdom(m); });
    // A segmenter more than a few seconds behind its sensor skips frames rather than queue MBs.
    inbox.setQueueCapacity(scan_ch, 30);
    inbox.setQueueCapacity(rgbd_ch, 30);
    app::installStopHandlers();
    spdlog::info("robot {}: {} + {} + {} -> {} on {} (lidar mode {})", robot, scan_ch, rgbd_ch, odom_ch, out_ch, url,
                 cfg.lidar_mode);
    msg::StatusBeacon status(lcm, status_ch, robot, "segmenter");
    auto counts = [&](bool now) { status.tick(node.published(), inbox.dropped(), node.issues().total(), now); };
    while (!app::stopRequested()) {
      if (lcm.handleTimeout(200) < 0 && !app::stopRequested()) throw std::runtime_error("LCM receive failed on " + url);
      node.report(app::steadySeconds());
      counts(false);
    }
    counts(true);
    spdlog::info("stopping after {} frames; skipped bad input: {}; dropped messages: {}", node.published(),
                 node.issues().empty() ? "none" : node.issues().summary(),
                 inbox.dropped() ? inbox.summary() : "none");
    return 0;
  });
}
