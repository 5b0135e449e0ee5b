#include "viewer_node.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "msg/convert.h"
#include "slide/frame_instances_t.hpp"
#include "slide/keypose_bundle_t.hpp"
#include "slide/loop_closure_t.hpp"
#include "slide/object_map_t.hpp"
#include "slide/optimizer_status_t.hpp"
#include "slide/stream_status_t.hpp"
#include "slide/sync_ack_t.hpp"
#include "slide/sync_chunk_t.hpp"
#include "slide/sync_heartbeat_t.hpp"
#include "slide/trajectory_t.hpp"

namespace slide {

namespace {
constexpr std::size_t kOdomMemory = 256;  // key poses whose odometry is remembered per robot

template <class M>
bool decodeExact(const void* data, std::size_t size, M& m) {
  if (size > static_cast<std::size_t>(INT_MAX)) return false;
  try {
    return m.decode(data, 0, static_cast<int>(size)) == static_cast<int>(size);
  } catch (const std::exception&) {
    return false;
  }
}

std::string cut(const std::string& s, std::size_t n) { return s.size() <= n ? s : s.substr(0, n) + "..."; }
}  // namespace

ViewerNode::ViewerNode(viewer::Scene& scene, ViewerNodeParams params, ViewerChannels channels)
    : scene_(scene), params_(params), ch_(std::move(channels)) {}

bool ViewerNode::wantsRobotChannel(const std::string& c) const {
  const std::vector<std::string> all = ch_.robotBus();
  return std::find(all.begin(), all.end(), c) != all.end();
}

bool ViewerNode::wantsTeamChannel(const std::string& c) const {
  const std::vector<std::string> all = ch_.teamBus();
  return std::find(all.begin(), all.end(), c) != all.end();
}

bool ViewerNode::drop(const std::string& channel, const std::string& reason) {
  ++drops_[channel][reason];
  return false;
}

bool ViewerNode::finitePose(const Pose& T) const {
  return T.matrix().allFinite() && T.translation().cwiseAbs().maxCoeff() <= params_.max_coordinate;
}

void ViewerNode::reset() { memory_.clear(); }

bool ViewerNode::onRobotBus(int view, const std::string& channel, const void* data, std::size_t size, double t) {
  ++received_;
  if (channel == ch_.object_map) return onObjectMap(view, channel, data, size, t);
  if (channel == ch_.trajectory) return onTrajectory(view, channel, data, size, t);
  if (channel == ch_.keypose_bundle) return onKeyPoseBundle(view, channel, data, size, t);
  if (channel == ch_.instances) return onInstances(view, channel, data, size, t);
  if (channel == ch_.loop_closure) return onLoopClosure(view, channel, data, size, t);
  if (channel == ch_.optimizer_status) return onOptimizerStatus(view, channel, data, size, t);
  if (channel == ch_.sensor_status) return onSensorStatus(view, channel, data, size, t);
  --received_;
  return true;
}

bool ViewerNode::onObjectMap(int view, const std::string& ch, const void* data, std::size_t size, double t) {
  object_map_t m{};
  if (!decodeExact(data, size, m)) return drop(ch, "undecodable");
  if (m.robot != view || m.frame_robot != view) return drop(ch, "not this robot's own map");
  if (m.num_objects > params_.max_objects) return drop(ch, "too many objects");
  std::vector<Object> objects;
  objects.reserve(m.objects.size());
  for (const object_t& o : m.objects) {
    try {
      Object obj = msg::fromLcm(o);
      if (obj.isFinite() && obj.position().cwiseAbs().maxCoeff() <= params_.max_coordinate &&
          obj.extent().cwiseAbs().maxCoeff() <= params_.max_extent) {
        objects.push_back(std::move(obj));
        continue;
      }
    } catch (const std::exception&) {  // not exactly one model
    }
    ++dropped_objects_;
  }
  scene_.setObjectMap(view, objects, t);
  return true;
}

bool ViewerNode::onTrajectory(int view, const std::string& ch, const void* data, std::size_t size, double t) {
  trajectory_t m{};
  if (!decodeExact(data, size, m)) return drop(ch, "undecodable");
  if (m.frame_robot != view) return drop(ch, "in another robot's frame");
  std::vector<Eigen::Vector3d> positions;
  std::map<int, Pose> optimized;
  for (int i = 0; i < m.num_poses; ++i) {
    if (!msg::usablePose(m.poses[i])) return drop(ch, "non-finite or absurd pose");
    const Pose T = msg::fromLcm(m.poses[i]);
    if (!finitePose(T)) return drop(ch, "non-finite or absurd pose");
    positions.push_back(T.translation());
    if (m.robot == view) optimized[m.keypose_seq[i]] = T;
  }
  scene_.setTrajectory(view, m.robot, positions, t);
  if (m.robot == view) {
    RobotMemory& mem = memory_[view];
    mem.optimized = std::move(optimized);
    updateCorrection(mem);
  }
  return true;
}

void ViewerNode::updateCorrection(RobotMemory& mem) {
  for (auto it = mem.odom.rbegin(); it != mem.odom.rend(); ++it) {
    auto opt = mem.optimized.find(it->first);
    if (opt == mem.optimized.end()) continue;
    mem.correction = opt->second * it->second.inverse();
    return;
  }
}

bool ViewerNode::onKeyPoseBundle(int view, const std::string& ch, const void* data, std::size_t size, double t) {
  keypose_bundle_t m{};
  if (!decodeExact(data, size, m)) return drop(ch, "undecodable");
  if (m.header.robot != view) return drop(ch, "another robot's bundle");
  if (!msg::usablePose(m.odom_pose)) return drop(ch, "non-finite or absurd pose");
  const Pose T_odom_body = msg::fromLcm(m.odom_pose);
  if (!finitePose(T_odom_body)) return drop(ch, "non-finite or absurd pose");
  RobotMemory& mem = memory_[view];
  mem.odom.emplace_back(m.header.seq, T_odom_body);
  if (mem.odom.size() > kOdomMemory) mem.odom.pop_front();
  updateCorrection(mem);
  scene_.setKeyPose(view, m.header.seq, mem.correction * T_odom_body, t);
  return true;
}

bool ViewerNode::onInstances(int view, const std::string& ch, const void* data, std::size_t size, double t) {
  frame_instances_t m{};
  if (!decodeExact(data, size, m)) return drop(ch, "undecodable");
  if (m.header.robot != view) return drop(ch, "another robot's instances");
  if (m.num_instances > params_.max_instances) return drop(ch, "too many instances");
  if (!msg::usablePose(m.odom_pose)) return drop(ch, "non-finite or absurd pose");
  const Pose T_frame_body = memory_[view].correction * msg::fromLcm(m.odom_pose);
  if (!finitePose(T_frame_body)) return drop(ch, "non-finite or absurd pose");
  std::vector<viewer::InstanceView> raw;
  for (const object_instance_t& o : m.instances) {
    viewer::InstanceView v{o.class_id, {}};
    v.points.reserve(o.xyz.size());
    for (const auto& p : o.xyz)
      if (p.size() == 3) v.points.emplace_back(p[0], p[1], p[2]);
    raw.push_back(std::move(v));
  }
  std::vector<viewer::InstanceView> thin = viewer::thinInstances(std::move(raw), params_.max_instance_points);
  const Eigen::Isometry3f T = T_frame_body.cast<float>();
  for (auto& inst : thin)
    for (auto& p : inst.points) p = T * p;
  scene_.setInstances(view, thin, t);
  return true;
}

bool ViewerNode::onLoopClosure(int view, const std::string& ch, const void* data, std::size_t size, double t) {
  loop_closure_t m{};
  if (!decodeExact(data, size, m)) return drop(ch, "undecodable");
  for (double v : {m.x, m.y, m.z, m.yaw, m.score})
    if (!std::isfinite(v)) return drop(ch, "non-finite transform");
  if (std::abs(m.x) > params_.max_coordinate || std::abs(m.y) > params_.max_coordinate ||
      std::abs(m.z) > params_.max_coordinate)
    return drop(ch, "absurd transform");
  if (m.num_inliers > params_.max_inliers) return drop(ch, "too many inliers");
  viewer::LoopView lc;
  lc.robot_a = m.robot_a, lc.robot_b = m.robot_b, lc.keypose_a = m.keypose_a, lc.keypose_b = m.keypose_b;
  lc.method = m.method == loop_closure_t::SLIDEGRAPH ? "slidegraph" : "slidematch";
  lc.x = m.x, lc.y = m.y, lc.z = m.z, lc.yaw = m.yaw, lc.score = m.score;
  lc.inliers_a = m.inliers_a;
  lc.inliers_b = m.inliers_b;
  scene_.addLoopClosure(view, lc, t);
  return true;
}

bool ViewerNode::onOptimizerStatus(int view, const std::string& ch, const void* data, std::size_t size, double t) {
  optimizer_status_t m{};
  if (!decodeExact(data, size, m)) return drop(ch, "undecodable");
  if (m.robot != view) return drop(ch, "another robot's status");
  if (!std::isfinite(m.update_ms)) return drop(ch, "non-finite update time");
  viewer::OptimizerView s;
  s.keyposes = m.num_keyposes, s.landmarks = m.num_landmarks, s.peers_merged = m.num_peers_merged;
  s.update_ms = m.update_ms, s.full_solve = m.full_solve;
  s.rejected = m.rejected_inputs, s.dropped = m.dropped_messages;
  scene_.setOptimizer(view, s, t);
  return true;
}

bool ViewerNode::onSensorStatus(int view, const std::string& ch, const void* data, std::size_t size, double t) {
  stream_status_t m{};
  if (!decodeExact(data, size, m)) return drop(ch, "undecodable");
  if (m.robot != view) return drop(ch, "another robot's status");
  viewer::SensorView s;
  s.state = m.state == stream_status_t::RUNNING    ? "running"
            : m.state == stream_status_t::FINISHED ? "finished"
            : m.state == stream_status_t::FAILED   ? "failed"
                                                   : "unknown";
  s.frames_sent = m.frames_sent, s.frames_total = m.frames_total;
  s.source = cut(m.source, params_.max_string);
  s.detections = cut(m.detections, params_.max_string);
  s.reason = cut(m.reason, params_.max_string);
  scene_.setSensor(view, s, t);
  return true;
}

bool ViewerNode::onTeamBus(int listener, const std::string& channel, const void* data, std::size_t size, double t) {
  int sender = -1;
  if (channel == ch_.team_heartbeat) {
    sync_heartbeat_t m{};
    if (!decodeExact(data, size, m)) return drop(channel, "undecodable");
    sender = m.sender;
  } else if (channel == ch_.team_chunk) {
    sync_chunk_t m{};
    if (!decodeExact(data, size, m)) return drop(channel, "undecodable");
    sender = m.sender;
  } else if (channel == ch_.team_ack) {
    sync_ack_t m{};
    if (!decodeExact(data, size, m)) return drop(channel, "undecodable");
    sender = m.sender;
  } else {
    return true;
  }
  ++received_;
  if (sender < 0) return drop(channel, "negative sender");
  scene_.noteTeamMessage(listener, sender, size, t);
  return true;
}

std::uint64_t ViewerNode::dropped() const {
  std::uint64_t n = 0;
  for (const auto& [c, reasons] : drops_)
    for (const auto& [r, k] : reasons) n += k;
  return n;
}

std::string ViewerNode::dropSummary() const {
  std::string s;
  for (const auto& [c, reasons] : drops_)
    for (const auto& [r, k] : reasons) s += (s.empty() ? "" : "; ") + c + ": " + std::to_string(k) + " " + r;
  return s;
}

}  // namespace slide
