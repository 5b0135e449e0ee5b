// slide-segmenter: SCAN (slide.lidar_scan_t) and RGBD (slide.rgbd_frame_t) in, per-frame
// object instances with the odometry pose of the frame (slide.frame_instances_t) out on
// INSTANCES. Frames wait for the ODOM messages around their time.
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <deque>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <variant>

#include "app/app.h"
#include "frontend/frontend_config.h"
#include "frontend/odometry_buffer.h"
#include "frontend_msg/frontend_convert.h"
#include "msg/convert.h"
#include "msg/inbox.h"
#include "msg/status_beacon.h"
#include "slide/odometry_t.hpp"

using namespace slide;

namespace {
std::atomic<bool> g_stop{false};

double nowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

class SegmenterNode {
 public:
  SegmenterNode(lcm::LCM& lcm, int robot, std::string out_channel, const ClassTable& classes, const FrontendConfig& cfg,
                std::size_t max_pending)
      : lcm_(lcm), robot_(robot), out_channel_(std::move(out_channel)), classes_(classes), cfg_(cfg),
        labelled_(classes, cfg.labelled), geometric_(classes, cfg.geometric), max_pending_(max_pending) {}

  void onScan(const lcm::ReceiveBuffer*, const std::string&, const lidar_scan_t* m) {
    pending_.emplace_back(*m);
    process();
  }
  void onRgbd(const lcm::ReceiveBuffer*, const std::string&, const rgbd_frame_t* m) {
    pending_.emplace_back(*m);
    process();
  }
  void onOdom(const lcm::ReceiveBuffer*, const std::string&, const odometry_t* m) {
    odom_.add(m->header.utime, fromMsg(m->pose));
    process();
  }
  void report() {
    if (auto text = window_.due(nowSeconds())) spdlog::warn("{}", *text);
  }
  int published() const { return published_; }
  const InputIssues& issues() const { return window_.total(); }

 private:
  using Frame = std::variant<lidar_scan_t, rgbd_frame_t>;

  static const header_t& headerOf(const Frame& f) {
    return std::visit([](const auto& m) -> const header_t& { return m.header; }, f);
  }

  // Segments every pending frame whose odometry pose is known, in arrival order.
  void process() {
    InputIssues issues;
    while (!pending_.empty()) {
      const std::int64_t utime = headerOf(pending_.front()).utime;
      const auto pose = odom_.at(utime);
      if (!pose) {
        if (odom_.hopeless(utime) || pending_.size() > max_pending_) {
          issues.count("frame without odometry");
          pending_.pop_front();
          continue;
        }
        break;
      }
      FrameInstances out;
      out.utime = utime;
      out.odom_pose = *pose;
      bool usable = true;  // bad frames (empty scans, unusable images) are skipped, not published
      if (const auto* scan = std::get_if<lidar_scan_t>(&pending_.front())) {
        const LabelledScan s = scanFromMsg(*scan, issues);
        const bool labelled = cfg_.lidar_mode == "labelled" || (cfg_.lidar_mode == "auto" && s.hasLabels());
        usable = s.size() > 0;
        if (!usable) issues.count("empty scan");
        else out.instances = labelled ? labelled_.segment(s, issues) : geometric_.segment(s, issues);
      } else if (auto frame = rgbdFromMsg(std::get<rgbd_frame_t>(pending_.front()), issues)) {
        out.instances = segmentRgbd(*frame, classes_, cfg_.rgbd, issues);
      } else {
        usable = false;
      }
      if (!usable) {
        pending_.pop_front();
        continue;
      }
      header_t h;
      h.utime = utime;
      h.robot = robot_;
      h.seq = seq_++;
      const frame_instances_t msg = instancesToMsg(out, h);
      lcm_.publish(out_channel_, &msg);
      ++published_;
      spdlog::debug("frame {}: {} instances", h.seq, out.instances.size());
      pending_.pop_front();
    }
    window_.add(issues);
  }

  lcm::LCM& lcm_;
  int robot_;
  std::string out_channel_;
  const ClassTable& classes_;
  const FrontendConfig& cfg_;
  LabelledSegmenter labelled_;
  GeometricSegmenter geometric_;
  std::size_t max_pending_;
  OdometryBuffer odom_;
  std::deque<Frame> pending_;
  IssueWindow window_;
  int seq_ = 0;
  int published_ = 0;
};
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Segmenter daemon: LiDAR scans (labelled or geometric mode) and RGBD frames (instance masks) "
               "to per-frame object instances stamped with their odometry pose"};
  CommonOptions common;
  addCommonOptions(app, common);
  int robot = 0;
  std::string url, config_file = std::string(SLIDE_SOURCE_DIR) + "/config/frontend.yaml";
  std::string classes_file = std::string(SLIDE_SOURCE_DIR) + "/config/classes.yaml";
  std::string scan_ch = "SCAN", rgbd_ch = "RGBD", odom_ch = "ODOM", out_ch = "INSTANCES", status_ch = "DAEMON_STATUS", mode;
  std::size_t max_pending = 50;
  app.add_option("--robot", robot, "Robot id")->capture_default_str();
  app.add_option("--lcm-url", url, "Robot bus URL (default udpm://239.255.76.67:<7667+robot>?ttl=0&recv_buf_size=4194304)");
  app.add_option("--config", config_file, "Front-end YAML")->capture_default_str();
  app.add_option("--classes", classes_file, "Class table YAML")->capture_default_str();
  app.add_option("--mode", mode, "LiDAR mode, overrides the config: auto | labelled | geometric")
      ->check(CLI::IsMember({"auto", "labelled", "geometric"}));
  app.add_option("--scan-channel", scan_ch, "LiDAR scans in")->capture_default_str();
  app.add_option("--rgbd-channel", rgbd_ch, "RGBD frames in")->capture_default_str();
  app.add_option("--odom-channel", odom_ch, "Odometry in")->capture_default_str();
  app.add_option("--instances-channel", out_ch, "Instances out")->capture_default_str();
  app.add_option("--status-channel", status_ch, "Counts out (daemon_status_t every 5 s)")->capture_default_str();
  app.add_option("--max-pending", max_pending, "Frames kept waiting for odometry")->capture_default_str();
  return runApp(app, common, argc, argv, [&]() {
    if (url.empty()) url = slide::robotBusUrl(robot);
    const ClassTable classes = ClassTable::load(classes_file);
    FrontendConfig cfg = loadFrontendConfig(config_file);
    if (!mode.empty()) cfg.lidar_mode = mode;
    lcm::LCM lcm(url);
    if (!lcm.good()) throw std::runtime_error("cannot open LCM at " + url);
    SegmenterNode node(lcm, robot, out_ch, classes, cfg, max_pending);
    msg::Inbox inbox(lcm);
    inbox.subscribe(scan_ch, &SegmenterNode::onScan, &node);
    inbox.subscribe(rgbd_ch, &SegmenterNode::onRgbd, &node);
    inbox.subscribe(odom_ch, &SegmenterNode::onOdom, &node);
    std::signal(SIGINT, [](int) { g_stop = true; });
    std::signal(SIGTERM, [](int) { g_stop = true; });
    spdlog::info("robot {}: {} + {} + {} -> {} on {} (lidar mode {})", robot, scan_ch, rgbd_ch, odom_ch, out_ch, url,
                 cfg.lidar_mode);
    msg::StatusBeacon status(lcm, status_ch, robot, "segmenter");
    auto counts = [&](bool now) { status.tick(node.published(), inbox.dropped(), node.issues().total(), now); };
    while (!g_stop) {
      if (lcm.handleTimeout(200) < 0 && !g_stop) throw std::runtime_error("LCM receive failed on " + url);
      node.report();
      counts(false);
    }
    counts(true);
    spdlog::info("stopping after {} frames; skipped bad input: {}; dropped messages: {}", node.published(),
                 node.issues().empty() ? "none" : node.issues().summary(),
                 inbox.dropped() ? inbox.summary() : "none");
    return 0;
  });
}
