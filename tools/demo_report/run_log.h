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
};

// Reads one robot bus log; messages that fail to decode are counted in `bad` and skipped.
RobotRunLog readRobotLog(const std::string& path, int robot, int& bad);

// Total bytes and messages per channel of a log (the team bus: what crossed the network).
struct ChannelTraffic {
  std::int64_t bytes = 0, messages = 0;
};
std::map<std::string, ChannelTraffic> readTraffic(const std::string& path);

}  // namespace slide
