// slide-loop-closer: own map, trajectory and peers' maps in; loop closures out. Place
// recognition runs here, in its own process, off the optimizer's path.
#include <lcm/lcm-cpp.hpp>
#include <spdlog/spdlog.h>

#include <chrono>
#include <csignal>

#include "app/app.h"
#include "config/config.h"
#include "msg/convert.h"
#include "msg/inbox.h"
#include "msg/status_beacon.h"
#include "place/loop_closer_config.h"
#include "slide/loop_closure_t.hpp"
#include "slide/object_map_t.hpp"
#include "slide/trajectory_t.hpp"

namespace {
volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

double nowS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
std::int64_t utimeNow() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

struct Channels {
  std::string own_map = "OBJECT_MAP", peer_maps = "PEER_MAP", trajectory = "TRAJECTORY", loop_closures = "LOOP_CLOSURE";
  std::string status = "DAEMON_STATUS";
};

// Objects farther than this from the map's origin are no robot's (they would overflow the
// place recognisers' float and int geometry): dropped, and counted in `dropped`.
constexpr double kMaxObjectCoordinate = 1e6;

slide::ObjectMap mapFromMsg(const slide::object_map_t& m, int& dropped) {
  slide::ObjectMap map;
  for (const slide::object_t& o : m.objects) {
    const slide::Object obj = slide::fromMsg(o);
    if (obj.isFinite() && obj.position().cwiseAbs().maxCoeff() <= kMaxObjectCoordinate) map.add(obj);
    else ++dropped;
  }
  return map;
}

class Node {
 public:
  Node(lcm::LCM& lcm, slide::LoopCloser& closer, int robot, Channels ch)
      : lcm_(lcm), inbox_(lcm), closer_(closer), robot_(robot), ch_(std::move(ch)) {
    inbox_.subscribe(ch_.own_map, &Node::onMap, this);
    if (ch_.peer_maps != ch_.own_map) inbox_.subscribe(ch_.peer_maps, &Node::onMap, this);
    inbox_.subscribe(ch_.trajectory, &Node::onTrajectory, this);
  }
  const slide::msg::Inbox& inbox() const { return inbox_; }
  long droppedObjects() const { return dropped_objects_; }
  long published() const { return published_; }

  void onMap(const lcm::ReceiveBuffer*, const std::string& channel, const slide::object_map_t* m) {
    if (m->frame_robot != m->robot) {
      spdlog::debug("{}: map of robot {} is in robot {}'s frame, skipped", channel, m->robot, m->frame_robot);
      return;
    }
    try {
      int dropped = 0;
      const slide::ObjectMap map = mapFromMsg(*m, dropped);
      if (dropped)
        spdlog::warn("{}: map of robot {}: dropped {} objects with non-finite numbers or beyond {} m", channel, m->robot,
                     dropped, kMaxObjectCoordinate);
      dropped_objects_ += dropped;
      const bool kept = m->robot == robot_ ? closer_.setOwnMap(map, nowS()) : closer_.setPeerMap(m->robot, map, nowS());
      if (!kept)
        spdlog::warn("{}: map of robot {} with {} objects dropped: more than max_map_objects ({} dropped so far)",
                     channel, m->robot, map.size(), closer_.counts().oversized_maps);
    } catch (const std::exception& e) {
      spdlog::warn("{}: map of robot {} rejected: {}", channel, m->robot, e.what());
    }
  }

  void onTrajectory(const lcm::ReceiveBuffer*, const std::string& channel, const slide::trajectory_t* m) {
    if (m->robot != robot_ || m->frame_robot != robot_) return;
    std::vector<slide::KeyPose> kps;
    for (int i = 0; i < m->num_poses; ++i) kps.push_back({m->keypose_seq[i], slide::fromMsg(m->poses[i])});
    closer_.setTrajectory(std::move(kps));
  }

  void publish(const slide::LoopClosure& lc) {
    slide::loop_closure_t out;
    out.utime = utimeNow();
    out.robot_a = lc.robot_a;
    out.robot_b = lc.robot_b;
    out.keypose_a = lc.keypose_a;
    out.keypose_b = lc.keypose_b;
    out.method = lc.method == slide::PlaceMethod::SlideGraph ? slide::loop_closure_t::SLIDEGRAPH
                                                             : slide::loop_closure_t::SLIDEMATCH;
    const Eigen::Vector4d v = slide::xyzYawOf(lc.T_a_b);
    out.x = v[0], out.y = v[1], out.z = v[2], out.yaw = v[3];
    out.score = lc.result.score;
    out.residual_rms = lc.result.residual_rms;
    out.num_inliers = static_cast<int32_t>(lc.inliers.size());
    for (const auto& [a, b] : lc.inliers) {
      out.inliers_a.push_back(a);
      out.inliers_b.push_back(b);
    }
    lcm_.publish(ch_.loop_closures, &out);
    ++published_;
  }

 private:
  lcm::LCM& lcm_;
  slide::msg::Inbox inbox_;
  slide::LoopCloser& closer_;
  int robot_;
  Channels ch_;
  long dropped_objects_ = 0;
  long published_ = 0;
};
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Loop closer: intra-robot (by proximity, against the robot's older objects) and inter-robot (own map\n"
               "against each peer's map, staggered, re-checked when maps change) place recognition; publishes\n"
               "slide.loop_closure_t after a consensus filter over repeated results.",
               "slide-loop-closer"};
  slide::CommonOptions common;
  slide::addCommonOptions(app, common);
  std::string config_path = std::string(SLIDE_SOURCE_DIR) + "/config/loop_closer.yaml", url, method;
  int robot = -1;
  app.add_option("--config", config_path, "Loop-closer configuration")->capture_default_str();
  app.add_option("--robot", robot, "Own robot id (overrides the config)");
  app.add_option("--lcm-url", url, "LCM URL of the robot bus (overrides the config; default udpm://239.255.76.67:<7667+robot>?ttl=0&recv_buf_size=4194304)");
  app.add_option("--method", method, "slidegraph or slidematch (overrides the config)")
      ->check(CLI::IsMember({"slidegraph", "slidematch"}));
  return slide::runApp(app, common, argc, argv, [&]() {
    const slide::ConfigNode cfg = slide::ConfigNode::load(config_path);
    slide::LoopCloserParams params = slide::loadLoopCloserParams(cfg);
    Channels ch;
    std::string cfg_url;
    if (cfg.has("lcm")) {
      const slide::ConfigNode l = cfg.child("lcm");
      cfg_url = l.get<std::string>("url", cfg_url);
      ch.own_map = l.get<std::string>("own_map", ch.own_map);
      ch.peer_maps = l.get<std::string>("peer_maps", ch.peer_maps);
      ch.trajectory = l.get<std::string>("trajectory", ch.trajectory);
      ch.loop_closures = l.get<std::string>("loop_closures", ch.loop_closures);
      ch.status = l.get<std::string>("status", ch.status);
    }
    cfg.rejectUnknownKeys();
    if (robot >= 0) params.robot = robot;
    if (!method.empty()) params.method = slide::parsePlaceMethod(method);
    if (url.empty()) url = cfg_url;
    if (url.empty()) url = slide::robotBusUrl(params.robot);

    lcm::LCM lcm(url);
    if (!lcm.good()) throw std::runtime_error("cannot open LCM at '" + url + "'");
    slide::LoopCloser closer(params);
    Node node(lcm, closer, params.robot, ch);
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    spdlog::info("robot {}: {} on {}, maps '{}'/'{}', trajectory '{}', out '{}'", params.robot,
                 slide::methodName(params.method), url, ch.own_map, ch.peer_maps, ch.trajectory, ch.loop_closures);
    std::string last_reason;
    long budget_exceeded = 0;
    slide::msg::StatusBeacon status(lcm, ch.status, params.robot, "loop_closer");
    auto counts = [&](bool now) {
      status.tick(node.published(), node.inbox().dropped(),
                  node.droppedObjects() + closer.counts().oversized_maps + closer.counts().budget_exceeded, now);
    };
    while (!g_stop) {
      counts(false);
      if (lcm.handleTimeout(100) < 0) {
        if (g_stop) break;  // select() interrupted by the stop signal
        throw std::runtime_error("LCM receive failed on '" + url + "'");
      }
      std::vector<slide::LoopClosure> found;
      try {
        found = closer.poll(nowS());
      } catch (const std::exception& e) {  // one bad map must not end the daemon
        spdlog::error("place recognition failed: {}", e.what());
      }
      for (const slide::LoopClosure& lc : found) {
        const Eigen::Vector4d v = slide::xyzYawOf(lc.T_a_b);
        spdlog::info("robot {} <- robot {}{}: {} ({} inliers, {:.1f} ms): x {:.3f} y {:.3f} z {:.3f} yaw {:.2f} deg",
                     lc.robot_a, lc.robot_b, lc.robot_a == lc.robot_b ? " (intra)" : "",
                     slide::outcomeName(lc.outcome), lc.inliers.size(), lc.result.ms, v[0], v[1], v[2],
                     v[3] * 180.0 / M_PI);
        if (lc.outcome != slide::ConsensusFilter::Outcome::Pending) node.publish(lc);
      }
      if (closer.counts().budget_exceeded > budget_exceeded) {
        budget_exceeded = closer.counts().budget_exceeded;
        spdlog::warn("place recognition gave no result: {} ({} checks over budget so far)", closer.lastReason(),
                     budget_exceeded);
      }
      if (closer.lastReason() != last_reason) {
        last_reason = closer.lastReason();
        if (!last_reason.empty()) spdlog::debug("no closure: {}", last_reason);
      }
    }
    counts(true);
    spdlog::info("stopping; dropped messages: {}; dropped map objects: {}; oversized maps dropped: {}; checks over "
                 "budget: {}",
                 node.inbox().dropped() ? node.inbox().summary() : "none", node.droppedObjects(),
                 closer.counts().oversized_maps, closer.counts().budget_exceeded);
    return 0;
  });
}
