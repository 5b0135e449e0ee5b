// slide-tracker: per-frame instances (INSTANCES, slide.frame_instances_t) in; tracks them in
// the odometry frame and, every key pose, publishes one observation bundle (relative odometry
// plus fitted objects in the body frame, slide.keypose_bundle_t) on KEYPOSE_BUNDLE.
#include <spdlog/spdlog.h>

#include <lcm/lcm-cpp.hpp>

#include "app/app.h"
#include "app/channels.h"
#include "app/clock.h"
#include "app/robot_bus.h"
#include "app/stop_signal.h"
#include "msg/inbox.h"
#include "msg/status_beacon.h"
#include "tracker_node.h"

using namespace slide;

int main(int argc, char** argv) {
  CLI::App app{"Tracker daemon: per-frame instances to tracked objects, one key-pose bundle (relative odometry "
               "and fitted cuboids/cylinders/ellipsoids in the body frame) every key pose"};
  app::CommonOptions common;
  app::addCommonOptions(app, common);
  app::RobotBusOptions bus;
  std::string config_file = std::string(SLIDE_SOURCE_DIR) + "/config/frontend.yaml";
  std::string classes_file = std::string(SLIDE_SOURCE_DIR) + "/config/classes.yaml";
  std::string in_ch = app::channels::kInstances, out_ch = app::channels::kKeyPoseBundle,
              status_ch = app::channels::kDaemonStatus;
  app::addRobotBusOptions(app, bus);
  app.add_option("--config", config_file, "Front-end YAML")->capture_default_str();
  app.add_option("--classes", classes_file, "Class table YAML")->capture_default_str();
  app.add_option("--instances-channel", in_ch, "Instances in")->capture_default_str();
  app.add_option("--bundle-channel", out_ch, "Key-pose bundles out")->capture_default_str();
  app.add_option("--status-channel", status_ch, "Counts out (daemon_status_t every 5 s)")->capture_default_str();
  return app::runApp(app, common, argc, argv, [&]() {
    const int robot = bus.robot;
    const std::string url = bus.resolve();
    const ClassTable classes = ClassTable::load(classes_file);
    const frontend::FrontendConfig cfg = frontend::loadFrontendConfig(config_file);
    lcm::LCM lcm(url);
    if (!lcm.good()) throw std::runtime_error("cannot open LCM at " + url);
    TrackerNode node(robot, out_ch, classes, cfg, msg::lcmPublisher(lcm));
    msg::Inbox inbox(lcm);
    inbox.subscribe<frame_instances_t>(in_ch, [&](auto&, auto& m) { node.onInstances(m); });
    app::installStopHandlers();
    spdlog::info("robot {}: {} -> {} on {} (key pose every {} m)", robot, in_ch, out_ch, url, cfg.keypose.distance);
    msg::StatusBeacon status(lcm, status_ch, robot, "tracker");
    auto counts = [&](bool now) { status.tick(node.bundles(), inbox.dropped(), node.issues().total(), now); };
    while (!app::stopRequested()) {
      if (lcm.handleTimeout(200) < 0 && !app::stopRequested()) throw std::runtime_error("LCM receive failed on " + url);
      node.report(app::steadySeconds());
      counts(false);
    }
    counts(true);
    spdlog::info("stopping after {} key poses; skipped bad input: {}; dropped messages: {}", node.bundles(),
                 node.issues().empty() ? "none" : node.issues().summary(),
                 inbox.dropped() ? inbox.summary() : "none");
    return 0;
  });
}
