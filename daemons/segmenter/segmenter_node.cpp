#include "segmenter_node.h"

#include <spdlog/spdlog.h>

#include "msg/frontend_convert.h"
#include "msg/convert.h"
#include "viewer/thin.h"

namespace slide {

namespace {
const header_t& headerOf(const std::variant<lidar_scan_t, rgbd_frame_t>& f) {
  return std::visit([](const auto& m) -> const header_t& { return m.header; }, f);
}
}  // namespace

SegmenterNode::SegmenterNode(int robot, std::string out_channel, const ClassTable& classes,
                             const frontend::FrontendConfig& cfg, std::size_t max_pending, msg::Publisher publish)
    : robot_(robot),
      out_channel_(std::move(out_channel)),
      classes_(classes),
      cfg_(cfg),
      labelled_(classes, cfg.labelled),
      geometric_(classes, cfg.geometric),
      max_pending_(max_pending),
      publish_(std::move(publish)) {
  if (cfg.lidar_mode == "learned")
    learned_ = std::make_unique<frontend::LearnedLidarSegmenter>(
        frontend::RangeNetLabeler::fromParams(cfg.learned),
        std::make_shared<frontend::LabelledSegmenter>(classes, cfg.labelled));
  if (!cfg.rgbd_detector.empty())
    detector_ = frontend::loadMaskDetector(cfg.rgbd_detector, classes);
}

void SegmenterNode::onScan(const lidar_scan_t& m) {
  pending_.emplace_back(m);
  process();
}

void SegmenterNode::onRgbd(const rgbd_frame_t& m) {
  pending_.emplace_back(m);
  process();
}

void SegmenterNode::onOdom(const odometry_t& m) {
  odom_.add(m.header.utime, msg::fromLcm(m.pose));
  process();
}

void SegmenterNode::report(double now_s) {
  if (auto text = window_.due(now_s)) spdlog::warn("{}", *text);
}

// Segments every pending frame whose odometry pose is known, in arrival order.
void SegmenterNode::process() {
  frontend::InputIssues issues;
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
    frontend::FrameInstances out;
    out.utime = utime;
    out.odom_pose = *pose;
    bool usable = true;  // bad frames (empty scans, unusable images) are skipped, not published
    if (const auto* scan = std::get_if<lidar_scan_t>(&pending_.front())) {
      const io::LabelledScan s = msg::fromLcm(*scan, issues);
      const bool labelled = cfg_.lidar_mode == "labelled" || (cfg_.lidar_mode == "auto" && s.hasLabels());
      const frontend::LidarSegmenter& seg = learned_   ? *learned_
                                            : labelled ? static_cast<const frontend::LidarSegmenter&>(labelled_)
                                                       : geometric_;
      usable = s.size() > 0;
      if (!usable) issues.count("empty scan");
      else out.instances = seg.segment(s, issues);
    } else if (auto frame = msg::fromLcm(std::get<rgbd_frame_t>(pending_.front()), issues)) {
      if (detector_) detector_->detect(*frame);
      out.instances = frontend::segmentRgbd(*frame, classes_, cfg_.rgbd, issues);
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
    publish_(out_channel_, msg::encodeLcm(msg::toLcm(out, h)));
    ++published_;
    spdlog::debug("frame {}: {} instances", h.seq, out.instances.size());
    const std::int64_t since = utime - last_preview_utime_;
    if (!preview_.channel.empty() && (previews_ == 0 || since < 0 || since >= preview_.period_s * 1e6)) {
      out.instances = viewer::thinInstances(std::move(out.instances), preview_.max_points);
      publish_(preview_.channel, msg::encodeLcm(msg::toLcm(out, h)));
      last_preview_utime_ = utime;
      ++previews_;
    }
    pending_.pop_front();
  }
  window_.add(issues);
}

}  // namespace slide
