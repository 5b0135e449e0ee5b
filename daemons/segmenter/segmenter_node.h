#pragma once
// The segmenter daemon's logic without the LCM loop: LiDAR scans and RGBD frames wait for the
// odometry around their time, then are segmented (labelled, geometric or learned LiDAR mode,
// RGBD masks) into per-frame object instances stamped with their odometry pose, published in
// arrival order through an injected publisher, and (setPreview) a thinned copy of some of them
// for the viewer and the run logs. Bad frames (empty scans, unusable images, frames whose
// odometry never comes) are skipped and counted, never published.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <variant>

#include "frontend/frontend_config.h"
#include "frontend/geometric_segmenter.h"
#include "frontend/input_issues.h"
#include "frontend/labelled_segmenter.h"
#include "frontend/odometry_buffer.h"
#include "frontend/mask_detector_loader.h"
#include "msg/publisher.h"
#include "slide/lidar_scan_t.hpp"
#include "slide/odometry_t.hpp"
#include "slide/rgbd_frame_t.hpp"

namespace slide {

class SegmenterNode {
 public:
  // `max_pending`: frames kept waiting for odometry (the oldest is dropped beyond it). In
  // learned mode (and with an RGBD detector) the model is loaded here: a missing, unreadable or
  // wrongly shaped model throws (the message names the file and what was expected).
  SegmenterNode(int robot, std::string out_channel, const ClassTable& classes, const frontend::FrontendConfig& cfg,
                std::size_t max_pending, msg::Publisher publish);

  // A thinned copy of the published instances (what the viewer draws; the run logs keep it where
  // they could not keep every scan's): at most one frame per `period_s` of frame time (and the
  // first after time went back), at most `max_points` points (viewer::thinInstances), on
  // `channel`; none while `channel` is empty (the default).
  struct Preview {
    std::string channel;
    double period_s = 0.5;
    std::size_t max_points = 200;
  };
  void setPreview(Preview p) { preview_ = std::move(p); }

  void onScan(const lidar_scan_t& m);
  void onRgbd(const rgbd_frame_t& m);
  void onOdom(const odometry_t& m);
  // Logs a summary of the skipped input when one is due at `now_s` (steady seconds).
  void report(double now_s);
  int published() const { return published_; }
  int previews() const { return previews_; }
  const frontend::InputIssues& issues() const { return window_.total(); }

 private:
  using Frame = std::variant<lidar_scan_t, rgbd_frame_t>;
  void process();

  int robot_;
  std::string out_channel_;
  const ClassTable& classes_;
  const frontend::FrontendConfig& cfg_;
  frontend::LabelledSegmenter labelled_;
  frontend::GeometricSegmenter geometric_;
  std::unique_ptr<frontend::LidarSegmenter> learned_;  // lidar_mode learned only
  std::unique_ptr<frontend::MaskDetector> detector_;  // rgbd.detector set only: masks from the colour image (and depth)
  std::size_t max_pending_;
  msg::Publisher publish_;
  frontend::OdometryBuffer odom_;
  std::deque<Frame> pending_;
  frontend::IssueWindow window_;
  int seq_ = 0;
  int published_ = 0;
  Preview preview_;
  std::int64_t last_preview_utime_ = 0;
  int previews_ = 0;
};

}  // namespace slide
