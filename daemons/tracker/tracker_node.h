#pragma once
// The tracker daemon's logic without the LCM loop: per-frame instances of this robot in,
// tracked in the odometry frame; every key pose one observation bundle (relative odometry plus
// fitted objects in the body frame) out through an injected publisher. Instances of another
// robot and bad instances are skipped and counted.
#include <string>

#include "frontend/frontend_config.h"
#include "frontend/input_issues.h"
#include "frontend/keypose.h"
#include "msg/publisher.h"
#include "slide/frame_instances_t.hpp"

namespace slide {

class TrackerNode {
 public:
  TrackerNode(int robot, std::string out_channel, const ClassTable& classes, const frontend::FrontendConfig& cfg,
              msg::Publisher publish);

  void onInstances(const frame_instances_t& m);
  // Logs a summary of the skipped input when one is due at `now_s` (steady seconds).
  void report(double now_s);
  int bundles() const { return bundler_.nextSeq(); }
  const frontend::InputIssues& issues() const { return window_.total(); }

 private:
  int robot_;
  std::string out_channel_;
  frontend::KeyPoseBundler bundler_;
  msg::Publisher publish_;
  frontend::IssueWindow window_;
};

}  // namespace slide
