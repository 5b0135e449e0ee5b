#pragma once
// Messages and LCM logs for the viewer's tests: a small robot-0 run (a car, a trunk and a bush in
// its map, its trajectory and robot 1's merged one, a key pose, instances, a loop closure, status)
// and robot 0's team-bus log (heartbeats from robot 1), written the way lcm-logger writes them.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "io/lcm_log.h"
#include "msg/convert.h"
#include "msg/publisher.h"
#include "slide/frame_instances_t.hpp"
#include "slide/keypose_bundle_t.hpp"
#include "slide/loop_closure_t.hpp"
#include "slide/object_map_t.hpp"
#include "slide/optimizer_status_t.hpp"
#include "slide/stream_status_t.hpp"
#include "slide/sync_heartbeat_t.hpp"
#include "slide/trajectory_t.hpp"

namespace slide::viewer_test {

inline Object car(std::int64_t id, double x, double y) {
  Cuboid c;
  c.pose = poseFromXyzYaw(x, y, 0.8, 0.3);
  c.dims = {4.5, 1.8, 1.6};
  return {id, 10, c, 0.9, 5};
}
inline Object trunk(std::int64_t id, double x, double y) {
  Cylinder c;
  c.root = {x, y, 0.0};
  c.radius = 0.3;
  c.length = 6.0;
  return {id, 71, c, 0.8, 4};
}
inline Object bush(std::int64_t id, double x, double y) {
  Ellipsoid e;
  e.centroid = {x, y, 0.6};
  e.radius = 1.0;
  e.height = 1.2;
  return {id, 0, e, 0.7, 3};
}

inline object_map_t mapMsg(int robot, const std::vector<Object>& objects, std::int64_t utime = 0) {
  object_map_t m;
  m.utime = utime;
  m.robot = m.frame_robot = robot;
  for (const Object& o : objects) m.objects.push_back(msg::toLcm(o));
  m.num_objects = static_cast<int32_t>(m.objects.size());
  return m;
}

// `n` key poses of `robot` in `frame`'s frame, 2 m apart along x from (x0, y0).
inline trajectory_t trajectoryMsg(int robot, int frame, int n, double x0, double y0) {
  trajectory_t m;
  m.robot = robot;
  m.frame_robot = frame;
  m.utime = 0;
  for (int i = 0; i < n; ++i) {
    m.keypose_seq.push_back(i);
    m.pose_utime.push_back(i * 100000);
    m.poses.push_back(msg::toLcm(poseFromXyzYaw(x0 + 2.0 * i, y0, 0.0, 0.0)));
  }
  m.num_poses = n;
  return m;
}

inline keypose_bundle_t bundleMsg(int robot, int seq, double x, double y) {
  keypose_bundle_t m{};
  m.header.robot = robot;
  m.header.seq = seq;
  m.odom_pose = msg::toLcm(poseFromXyzYaw(x, y, 0.0, 0.0));
  m.relative_odom = msg::toLcm(Pose::Identity());
  m.num_objects = 0;
  return m;
}

inline frame_instances_t instancesMsg(int robot, int points) {
  frame_instances_t m;
  m.header.robot = robot;
  m.header.seq = 1;
  m.header.utime = 0;
  m.odom_pose = msg::toLcm(Pose::Identity());
  object_instance_t o;
  o.instance_id = 1;
  o.class_id = 10;
  o.confidence = 0.9f;
  for (int i = 0; i < points; ++i) o.xyz.push_back({10.0f + 0.01f * i, 5.0f, 0.5f});
  o.num_points = points;
  o.num_free = 0;
  o.free_z = 0;
  m.instances.push_back(o);
  m.num_instances = 1;
  return m;
}

inline loop_closure_t loopMsg(int a, int b, std::vector<std::int64_t> inliers) {
  loop_closure_t m{};
  m.robot_a = a;
  m.robot_b = b;
  m.keypose_a = m.keypose_b = -1;
  m.method = loop_closure_t::SLIDEGRAPH;
  m.x = 1.0, m.y = 2.0, m.yaw = 0.1, m.score = 3;
  m.inliers_a = inliers;
  m.inliers_b = inliers;
  m.num_inliers = static_cast<int32_t>(inliers.size());
  return m;
}

inline optimizer_status_t optimizerMsg(int robot, int landmarks) {
  optimizer_status_t m{};
  m.robot = robot;
  m.num_keyposes = 20;
  m.num_landmarks = landmarks;
  m.update_ms = 12.5;
  return m;
}

inline stream_status_t sensorMsg(int robot, int sent, int total) {
  stream_status_t m{};
  m.robot = robot;
  m.state = stream_status_t::RUNNING;
  m.frames_sent = sent;
  m.frames_total = total;
  m.source = "test";
  m.detections = "none";
  return m;
}

inline sync_heartbeat_t heartbeatMsg(int sender, std::int64_t counter) {
  sync_heartbeat_t m{};
  m.sender = static_cast<int16_t>(sender);
  m.counter = counter;
  m.num_origins = 0;
  m.mac_size = 8;
  m.mac.assign(8, 0);
  return m;
}

// Appends messages to an LCM log as lcm-logger would.
class LogWriter {
 public:
  explicit LogWriter(const std::string& path, const char* mode = "wb") : f_(std::fopen(path.c_str(), mode)) {}
  ~LogWriter() {
    if (f_) std::fclose(f_);
  }
  bool good() const { return f_ != nullptr; }
  template <class M>
  bool write(const std::string& channel, const M& m, std::int64_t utime) {
    io::LcmLogEvent ev;
    ev.event_number = n_++;
    ev.utime = utime;
    ev.channel = channel;
    ev.data = msg::encodeLcm(m);
    return io::writeLcmLogEvent(f_, ev);
  }
  bool writeRaw(const std::string& channel, const std::vector<std::uint8_t>& bytes, std::int64_t utime) {
    return io::writeLcmLogEvent(f_, {n_++, utime, channel, bytes});
  }

 private:
  std::FILE* f_;
  std::int64_t n_ = 0;
};

// Robot 0's bus over one second of log time from `t0` (microseconds): status, trajectories, a key
// pose, instances, the map (car 1, trunk 2, bush 3) and a loop closure with the car and trunk.
inline void writeRobotRun(LogWriter& w, std::int64_t t0) {
  w.write("SENSOR_STATUS", sensorMsg(0, 40, 100), t0);
  w.write("TRAJECTORY", trajectoryMsg(0, 0, 20, 0.0, 0.0), t0 + 100000);
  w.write("TRAJECTORY", trajectoryMsg(1, 0, 10, 0.0, 10.0), t0 + 150000);
  w.write("KEYPOSE_BUNDLE", bundleMsg(0, 19, 38.0, 0.0), t0 + 200000);
  w.write("INSTANCES_PREVIEW", instancesMsg(0, 1000), t0 + 250000);
  w.write("OBJECT_MAP", mapMsg(0, {car(1, 10, 5), trunk(2, 20, -5), bush(3, 30, 5)}), t0 + 300000);
  w.write("OPTIMIZER_STATUS", optimizerMsg(0, 3), t0 + 350000);
  w.write("LOOP_CLOSURE", loopMsg(0, 1, {1, 2}), t0 + 400000);
}

}  // namespace slide::viewer_test
