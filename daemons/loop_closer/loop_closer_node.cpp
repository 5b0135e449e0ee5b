#include "loop_closer_node.h"

#include <spdlog/spdlog.h>

#include <cmath>

#include "app/clock.h"
#include "msg/convert.h"
#include "slide/loop_closure_t.hpp"

namespace slide {

namespace {
// Objects farther than this from the map's origin are no robot's (they would overflow the
// place recognisers' float and int geometry): dropped, and counted in `dropped`.
constexpr double kMaxObjectCoordinate = 1e6;

ObjectMap mapFromMsg(const object_map_t& m, int& dropped) {
  ObjectMap map;
  for (const object_t& o : m.objects) {
    const Object obj = msg::fromLcm(o);
    if (obj.isFinite() && obj.position().cwiseAbs().maxCoeff() <= kMaxObjectCoordinate) map.add(obj);
    else ++dropped;
  }
  return map;
}
}  // namespace

std::string readLoopCloserBus(const ConfigNode& cfg, LoopCloserChannels& ch) {
  if (!cfg.has("lcm")) return "";
  const ConfigNode l = cfg.child("lcm");
  ch.own_map = l.get<std::string>("own_map", ch.own_map);
  ch.peer_maps = l.get<std::string>("peer_maps", ch.peer_maps);
  ch.trajectory = l.get<std::string>("trajectory", ch.trajectory);
  ch.loop_closures = l.get<std::string>("loop_closures", ch.loop_closures);
  ch.status = l.get<std::string>("status", ch.status);
  return l.get<std::string>("url", "");
}

LoopCloserNode::LoopCloserNode(place::LoopCloserParams params, LoopCloserChannels channels, msg::Publisher publish)
    : params_(params), channels_(std::move(channels)), publish_(std::move(publish)), closer_(std::move(params)) {}

long LoopCloserNode::droppedInputs() const {
  return dropped_objects_ + closer_.counts().oversized_maps + closer_.counts().budget_exceeded;
}

void LoopCloserNode::onMap(const std::string& channel, const object_map_t& m, double now_s) {
  if (m.frame_robot != m.robot) {
    spdlog::debug("{}: map of robot {} is in robot {}'s frame, skipped", channel, m.robot, m.frame_robot);
    return;
  }
  try {
    int dropped = 0;
    const ObjectMap map = mapFromMsg(m, dropped);
    if (dropped)
      spdlog::warn("{}: map of robot {}: dropped {} objects with non-finite numbers or beyond {} m", channel, m.robot,
                   dropped, kMaxObjectCoordinate);
    dropped_objects_ += dropped;
    const bool kept = m.robot == params_.robot ? closer_.setOwnMap(map, now_s) : closer_.setPeerMap(m.robot, map, now_s);
    if (!kept)
      spdlog::warn("{}: map of robot {} with {} objects dropped: more than max_map_objects ({} dropped so far)", channel,
                   m.robot, map.size(), closer_.counts().oversized_maps);
  } catch (const std::exception& e) {
    spdlog::warn("{}: map of robot {} rejected: {}", channel, m.robot, e.what());
  }
}

void LoopCloserNode::onTrajectory(const trajectory_t& m) {
  if (m.robot != params_.robot || m.frame_robot != params_.robot) return;
  std::vector<place::KeyPose> kps;
  for (int i = 0; i < m.num_poses; ++i) kps.push_back({m.keypose_seq[i], msg::fromLcm(m.poses[i])});
  closer_.setTrajectory(std::move(kps));
}

void LoopCloserNode::poll(double now_s) {
  std::vector<place::LoopClosure> found;
  try {
    found = closer_.poll(now_s);
  } catch (const std::exception& e) {  // one bad map must not end the daemon
    spdlog::error("place recognition failed: {}", e.what());
  }
  for (const place::LoopClosure& lc : found) {
    const Eigen::Vector4d v = xyzYawOf(lc.T_a_b);
    const char* how = lc.result.by_shape        ? ", by shape family: the maps share too few classes"
                      : lc.result.by_tile_votes ? ", by SlideMatch's tile votes"
                                                : "";
    spdlog::info("robot {} <- robot {}{}: {} ({} inliers{}, {:.1f} ms): x {:.3f} y {:.3f} z {:.3f} yaw {:.2f} deg",
                 lc.robot_a, lc.robot_b, lc.robot_a == lc.robot_b ? " (intra)" : "", place::outcomeName(lc.outcome),
                 lc.inliers.size(), how, lc.result.ms, v[0], v[1], v[2], v[3] * 180.0 / M_PI);
    if (lc.outcome != place::ConsensusFilter::Outcome::Pending) publish(lc);
  }
  if (closer_.counts().budget_exceeded > budget_exceeded_) {
    budget_exceeded_ = closer_.counts().budget_exceeded;
    spdlog::warn("place recognition gave no result: {} ({} checks over budget so far)", closer_.lastReason(),
                 budget_exceeded_);
  }
  if (closer_.lastReason() != last_reason_) {
    last_reason_ = closer_.lastReason();
    if (!last_reason_.empty()) spdlog::debug("no closure: {}", last_reason_);
  }
}

void LoopCloserNode::publish(const place::LoopClosure& lc) {
  loop_closure_t out;
  out.utime = app::wallMicros();
  out.robot_a = lc.robot_a;
  out.robot_b = lc.robot_b;
  out.keypose_a = lc.keypose_a;
  out.keypose_b = lc.keypose_b;
  out.method = lc.method == place::PlaceMethod::SlideGraph ? loop_closure_t::SLIDEGRAPH : loop_closure_t::SLIDEMATCH;
  const Eigen::Vector4d v = xyzYawOf(lc.T_a_b);
  out.x = v[0], out.y = v[1], out.z = v[2], out.yaw = v[3];
  out.score = lc.result.score;
  out.residual_rms = lc.result.residual_rms;
  out.num_inliers = static_cast<int32_t>(lc.inliers.size());
  for (const auto& [a, b] : lc.inliers) {
    out.inliers_a.push_back(a);
    out.inliers_b.push_back(b);
  }
  publish_(channels_.loop_closures, msg::encodeLcm(out));
  ++published_;
}

}  // namespace slide
