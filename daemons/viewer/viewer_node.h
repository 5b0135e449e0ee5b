#pragma once
// The viewer daemon's logic without a bus, a log or a web server: raw LCM messages in (from a
// robot bus, or from the team bus as one robot or this host heard it), checked values out into
// a viewer::Scene. Every message is decoded defensively: it must decode to exactly its own
// size (the hardened lcm-gen decoders never over-read), and every number must be finite and
// within a robot's range, every count bounded; what fails is dropped and counted by channel and
// reason, never thrown. The viewer only listens: the node publishes nothing.
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "app/channels.h"
#include "geometry/pose.h"
#include "viewer/scene.h"

namespace slide {

struct ViewerChannels {
  std::string object_map = app::channels::kObjectMap;
  std::string trajectory = app::channels::kTrajectory;
  std::string keypose_bundle = app::channels::kKeyPoseBundle;
  std::string instances = app::channels::kInstancesPreview;  // the segmenter's thinned copy
  std::string loop_closure = app::channels::kLoopClosure;
  std::string optimizer_status = app::channels::kOptimizerStatus;
  std::string sensor_status = app::channels::kSensorStatus;
  std::string team_heartbeat = app::channels::kTeamHeartbeat;
  std::string team_chunk = app::channels::kTeamChunk;
  std::string team_ack = app::channels::kTeamAck;

  // What the viewer listens to on a robot bus, and on the team bus.
  std::vector<std::string> robotBus() const {
    return {object_map, trajectory, keypose_bundle, instances, loop_closure, optimizer_status, sensor_status};
  }
  std::vector<std::string> teamBus() const { return {team_heartbeat, team_chunk, team_ack}; }
};

struct ViewerNodeParams {
  std::size_t max_instance_points = 200;  // per scan, after thinning (the page's bandwidth)
  double max_coordinate = 1e6;            // m; farther is no robot's
  double max_extent = 1000.0;             // m; a larger object is absurd
  int max_objects = 200000;               // per map message
  int max_instances = 10000;              // per frame
  int max_inliers = 100000;               // per loop closure
  std::size_t max_string = 512;           // status strings are cut here
};

class ViewerNode {
 public:
  ViewerNode(viewer::Scene& scene, ViewerNodeParams params = {}, ViewerChannels channels = {});

  // The robot buses' channels the viewer draws (a replay reads only these).
  bool wantsRobotChannel(const std::string& channel) const;
  bool wantsTeamChannel(const std::string& channel) const;

  // One message from the bus of robot `view`, received at `t` (seconds); false when it was
  // dropped (undecodable or absurd; counted). Channels the viewer does not draw are ignored.
  bool onRobotBus(int view, const std::string& channel, const void* data, std::size_t size, double t);
  // One team-bus message heard by `listener` (robot id, or -1: this host); false when dropped.
  bool onTeamBus(int listener, const std::string& channel, const void* data, std::size_t size, double t);

  // "OBJECT_MAP: 2 undecodable; TRAJECTORY: 1 non-finite"; empty when nothing was dropped.
  std::string dropSummary() const;
  std::uint64_t dropped() const;
  std::uint64_t received() const { return received_; }
  // Objects dropped from maps that were otherwise drawn (non-finite, absurd, bad model).
  std::uint64_t droppedObjects() const { return dropped_objects_; }
  // Forgets what it remembered of trajectories and key poses (the scene was reset).
  void reset();

 private:
  struct RobotMemory {
    std::map<int, Pose> optimized;   // own trajectory, key-pose seq -> T_frame_body
    std::deque<std::pair<int, Pose>> odom;  // latest key poses' odometry, seq -> T_odom_body
    Pose correction = Pose::Identity();     // T_frame_odom from the newest seq in both
  };
  bool drop(const std::string& channel, const std::string& reason);
  bool finitePose(const Pose& T) const;
  void updateCorrection(RobotMemory& m);

  bool onObjectMap(int view, const std::string& ch, const void* data, std::size_t size, double t);
  bool onTrajectory(int view, const std::string& ch, const void* data, std::size_t size, double t);
  bool onKeyPoseBundle(int view, const std::string& ch, const void* data, std::size_t size, double t);
  bool onInstances(int view, const std::string& ch, const void* data, std::size_t size, double t);
  bool onLoopClosure(int view, const std::string& ch, const void* data, std::size_t size, double t);
  bool onOptimizerStatus(int view, const std::string& ch, const void* data, std::size_t size, double t);
  bool onSensorStatus(int view, const std::string& ch, const void* data, std::size_t size, double t);

  viewer::Scene& scene_;
  ViewerNodeParams params_;
  ViewerChannels ch_;
  std::map<int, RobotMemory> memory_;
  std::map<std::string, std::map<std::string, std::uint64_t>> drops_;  // channel -> reason -> count
  std::uint64_t received_ = 0, dropped_objects_ = 0;
};

}  // namespace slide
