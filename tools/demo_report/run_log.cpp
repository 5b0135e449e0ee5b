#include "run_log.h"

#include <lcm/lcm-cpp.hpp>
#include <stdexcept>

#include "app/channels.h"
#include "msg/convert.h"
#include "team/messages.h"
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
template <typename M>
bool decode(const lcm::LogEvent* ev, M& m) {
  return m.decode(ev->data, 0, ev->datalen) == ev->datalen;
}
}  // namespace

RobotRunLog readRobotLog(const std::string& path, int robot, int& bad) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw std::runtime_error(path + ": cannot open LCM log");
  RobotRunLog out;
  bad = 0;
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    const std::string& ch = ev->channel;
    if (ch == app::channels::kObjectMap) {
      object_map_t m;
      if (!decode(ev, m)) { ++bad; continue; }
      if (m.robot != robot) continue;
      out.map.clear();
      for (const object_t& o : m.objects) out.map.push_back(msg::fromLcm(o));
    } else if (ch == app::channels::kTrajectory) {
      trajectory_t m;
      if (!decode(ev, m)) { ++bad; continue; }
      LoggedTrajectory t{m.robot, m.frame_robot, {}, {}};
      for (int i = 0; i < m.num_poses; ++i) {
        t.t.push_back(m.pose_utime[i] * 1e-6);
        t.poses.push_back(msg::fromLcm(m.poses[i]));
      }
      out.trajectories[m.robot] = t;
    } else if (ch == app::channels::kLoopClosure) {
      loop_closure_t m;
      if (!decode(ev, m)) { ++bad; continue; }
      if (m.robot_a != robot || m.robot_b == robot) continue;
      out.closures[m.robot_b] = {m.robot_a, m.robot_b, m.num_inliers, poseFromXyzYaw(m.x, m.y, m.z, m.yaw),
                                 m.method == loop_closure_t::SLIDEMATCH ? "slidematch" : "slidegraph"};
    } else if (ch == app::channels::kOptimizerStatus) {
      optimizer_status_t m;
      if (!decode(ev, m)) { ++bad; continue; }
      out.update_ms.push_back(m.update_ms);
    } else if (ch == app::channels::kSensorStatus) {
      stream_status_t m;
      if (!decode(ev, m)) { ++bad; continue; }
      if (m.robot == robot) out.detections = m.detections;
    } else if (ch == app::channels::kKeyPoseBundle) {
      ++out.keypose_bundles;
    } else if (ch == app::channels::kPeerBundle) {
      ++out.peer_bundles;
    }
  }
  return out;
}

TeamTraffic& TeamTraffic::operator+=(const TeamTraffic& o) {
  bundles += o.bundles;
  maps += o.maps;
  heartbeats += o.heartbeats;
  acks += o.acks;
  payload += o.payload;
  messages += o.messages;
  undecodable += o.undecodable;
  return *this;
}

TeamTraffic readTeamTraffic(const std::string& path, int robot) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw std::runtime_error(path + ": cannot open LCM log");
  TeamTraffic out;
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    int sender = -1;
    std::int64_t* kind = nullptr;
    if (ev->channel == app::channels::kTeamHeartbeat) {
      sync_heartbeat_t m{};
      if (decode(ev, m)) sender = m.sender, kind = &out.heartbeats;
    } else if (ev->channel == app::channels::kTeamChunk) {
      sync_chunk_t m{};
      if (decode(ev, m)) {  // whole maps and map changes count as maps; an unknown kind as undecodable
        sender = m.sender;
        if (m.kind == sync_chunk_t::BUNDLE) kind = &out.bundles;
        if (m.kind == sync_chunk_t::MAP || m.kind == sync_chunk_t::MAP_DELTA) kind = &out.maps;
      }
    } else if (ev->channel == app::channels::kTeamAck) {
      sync_ack_t m{};
      if (decode(ev, m)) sender = m.sender, kind = &out.acks;
    } else {
      continue;
    }
    if (!kind) {
      ++out.undecodable;
    } else if (sender == robot) {
      *kind += static_cast<std::int64_t>(team::lcmWireBytes(ev->channel, static_cast<std::size_t>(ev->datalen)));
      out.payload += ev->datalen;
      ++out.messages;
    }
  }
  return out;
}

}  // namespace slide
