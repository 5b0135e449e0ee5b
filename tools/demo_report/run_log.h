#pragma once
// What a robot's daemons said during a run, read back from the LCM log of its robot bus
// (lcm-logger output): the last map and trajectories, the loop closures, the timings.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "geometry/pose.h"
#include "objects/object.h"

namespace slide {

struct LoggedTrajectory {
  int robot = 0;        // whose trajectory
  int frame_robot = 0;  // in whose frame
  std::vector<double> t;  // seconds
  std::vector<Pose> poses;
};

struct LoggedClosure {
  int robot_a = 0, robot_b = 0, inliers = 0;
  Pose T_a_b = Pose::Identity();
  std::string method;
};

struct RobotRunLog {
  std::vector<Object> map;                     // last OBJECT_MAP
  std::map<int, LoggedTrajectory> trajectories;  // last TRAJECTORY per robot
  std::map<int, LoggedClosure> closures;       // last inter-robot LOOP_CLOSURE per peer
  std::vector<double> update_ms;               // OPTIMIZER_STATUS
  int keypose_bundles = 0;                     // KEYPOSE_BUNDLE messages seen
  int peer_bundles = 0;                        // PEER_BUNDLE messages seen
  std::string detections;                      // SENSOR_STATUS: what the driver published (none / emulated / oracle)
};

// Reads one robot bus log; messages that fail to decode are counted in `bad` and skipped.
RobotRunLog readRobotLog(const std::string& path, int robot, int& bad);

// Team-bus traffic a robot sent, from the team-bus log recorded on its own host: messages of
// TEAM_HEARTBEAT / TEAM_CHUNK / TEAM_ACK whose sender is `robot`, so that summing the hosts'
// figures counts every message once, at its sender. Bytes are IPv4 bytes on the wire
// (team::lcmWireBytes: LCM header, channel, payload, UDP and IP headers), split by what the
// message carries.
struct TeamTraffic {
  std::int64_t bundles = 0, maps = 0, heartbeats = 0, acks = 0;  // wire bytes
  std::int64_t payload = 0;                                     // LCM payload bytes only
  std::int64_t messages = 0, undecodable = 0;
  std::int64_t bytes() const { return bundles + maps + heartbeats + acks; }
  TeamTraffic& operator+=(const TeamTraffic& o);
};
TeamTraffic readTeamTraffic(const std::string& path, int robot);

}  // namespace slide
