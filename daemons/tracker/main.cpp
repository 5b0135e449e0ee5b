// slide-tracker: per-frame instances (INSTANCES, slide.frame_instances_t) in; tracks them in
// the odometry frame and, every key pose, publishes one observation bundle (relative odometry
// plus fitted objects in the body frame, slide.keypose_bundle_t) on KEYPOSE_BUNDLE.
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <lcm/lcm-cpp.hpp>

#include "app/app.h"
#include "frontend/frontend_config.h"
#include "frontend_msg/frontend_convert.h"
#include "msg/inbox.h"
#include "msg/status_beacon.h"

using namespace slide;

namespace {
std::atomic<bool> g_stop{false};

double nowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

class TrackerNode {
 public:
  TrackerNode(lcm::LCM& lcm, int robot, std::string out_channel, const ClassTable& classes, const FrontendConfig& cfg)
      : lcm_(lcm), robot_(robot), out_channel_(std::move(out_channel)),
        bundler_(Tracker(classes, cfg.tracker, cfg.fit), cfg.keypose) {}

  void onInstances(const lcm::ReceiveBuffer*, const std::string&, const frame_instances_t* m) {
    InputIssues issues;
    if (m->header.robot != robot_) issues.count("instances of another robot");
    else if (const auto b = bundler_.process(instancesFromMsg(*m), issues)) {
      const keypose_bundle_t msg = bundleToMsg(*b, robot_);
      lcm_.publish(out_channel_, &msg);
      spdlog::debug("key pose {}: {} objects", b->seq, b->objects.size());
    }
    window_.add(issues);
  }
  void report() {
    if (auto text = window_.due(nowSeconds())) spdlog::warn("{}", *text);
  }
  int bundles() const { return bundler_.nextSeq(); }
  const InputIssues& issues() const { return window_.total(); }

 private:
  lcm::LCM& lcm_;
  int robot_;
  std::string out_channel_;
  KeyposeBundler bundler_;
  IssueWindow window_;
};
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Tracker daemon: per-frame instances to tracked objects, one key-pose bundle (relative odometry "
               "and fitted cuboids/cylinders/ellipsoids in the body frame) every key pose"};
  CommonOptions common;
  addCommonOptions(app, common);
  int robot = 0;
  std::string url, config_file = std::string(SLIDE_SOURCE_DIR) + "/config/frontend.yaml";
  std::string classes_file = std::string(SLIDE_SOURCE_DIR) + "/config/classes.yaml";
  std::string in_ch = "INSTANCES", out_ch = "KEYPOSE_BUNDLE", status_ch = "DAEMON_STATUS";
  app.add_option("--robot", robot, "Robot id")->capture_default_str();
  app.add_option("--lcm-url", url, "Robot bus URL (default udpm://239.255.76.67:<7667+robot>?ttl=0&recv_buf_size=4194304)");
  app.add_option("--config", config_file, "Front-end YAML")->capture_default_str();
  app.add_option("--classes", classes_file, "Class table YAML")->capture_default_str();
  app.add_option("--instances-channel", in_ch, "Instances in")->capture_default_str();
  app.add_option("--bundle-channel", out_ch, "Key-pose bundles out")->capture_default_str();
  app.add_option("--status-channel", status_ch, "Counts out (daemon_status_t every 5 s)")->capture_default_str();
  return runApp(app, common, argc, argv, [&]() {
    if (url.empty()) url = slide::robotBusUrl(robot);
    const ClassTable classes = ClassTable::load(classes_file);
    const FrontendConfig cfg = loadFrontendConfig(config_file);
    lcm::LCM lcm(url);
    if (!lcm.good()) throw std::runtime_error("cannot open LCM at " + url);
    TrackerNode node(lcm, robot, out_ch, classes, cfg);
    msg::Inbox inbox(lcm);
    inbox.subscribe(in_ch, &TrackerNode::onInstances, &node);
    std::signal(SIGINT, [](int) { g_stop = true; });
    std::signal(SIGTERM, [](int) { g_stop = true; });
    spdlog::info("robot {}: {} -> {} on {} (key pose every {} m)", robot, in_ch, out_ch, url, cfg.keypose.distance);
    msg::StatusBeacon status(lcm, status_ch, robot, "tracker");
    auto counts = [&](bool now) { status.tick(node.bundles(), inbox.dropped(), node.issues().total(), now); };
    while (!g_stop) {
      if (lcm.handleTimeout(200) < 0 && !g_stop) throw std::runtime_error("LCM receive failed on " + url);
      node.report();
      counts(false);
    }
    counts(true);
    spdlog::info("stopping after {} key poses; skipped bad input: {}; dropped messages: {}", node.bundles(),
                 node.issues().empty() ? "none" : node.issues().summary(),
                 inbox.dropped() ? inbox.summary() : "none");
    return 0;
  });
}
