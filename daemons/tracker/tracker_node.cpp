#include "tracker_node.h"

#include <spdlog/spdlog.h>

#include "msg/convert.h"
#include "msg/frontend_convert.h"

namespace slide {

TrackerNode::TrackerNode(int robot, std::string out_channel, const ClassTable& classes,
                         const frontend::FrontendConfig& cfg, msg::Publisher publish)
    : robot_(robot),
      out_channel_(std::move(out_channel)),
      bundler_(frontend::Tracker(classes, cfg.tracker, cfg.fit), cfg.keypose),
      publish_(std::move(publish)) {}

void TrackerNode::onInstances(const frame_instances_t& m) {
  frontend::InputIssues issues;
  if (m.header.robot != robot_) issues.count("instances of another robot");
  else if (auto b = bundler_.process(msg::fromLcm(m), issues)) {
    b->robot = robot_;
    publish_(out_channel_, msg::encodeLcm(msg::toLcm(*b)));
    spdlog::debug("key pose {}: {} objects", b->seq, b->objects.size());
  }
  window_.add(issues);
}

void TrackerNode::report(double now_s) {
  if (auto text = window_.due(now_s)) spdlog::warn("{}", *text);
}

}  // namespace slide
