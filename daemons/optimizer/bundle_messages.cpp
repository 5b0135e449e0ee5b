#include "bundle_messages.h"

#include <stdexcept>

#include "msg/convert.h"

namespace slide {

KeyPoseBundle fromMsg(const keypose_bundle_t& m, std::vector<std::string>& warnings) {
  KeyPoseBundle b;
  b.robot = m.header.robot;
  b.seq = m.header.seq;
  b.utime = m.header.utime;
  b.odom_pose = fromMsg(m.odom_pose);
  b.relative_odom = fromMsg(m.relative_odom);
  for (int i = 0; i < 6; ++i) b.odom_sigma[i] = m.odom_sigma[i];
  for (const object_t& o : m.objects) {
    try {
      b.objects.push_back(fromMsg(o));
    } catch (const std::invalid_argument& e) {
      warnings.push_back("robot " + std::to_string(b.robot) + " key pose " + std::to_string(b.seq) + ": " + e.what());
    }
  }
  return b;
}

keypose_bundle_t toMsg(const KeyPoseBundle& b) {
  keypose_bundle_t m;
  m.header.utime = b.utime;
  m.header.robot = b.robot;
  m.header.seq = b.seq;
  m.odom_pose = toMsg(b.odom_pose);
  m.relative_odom = toMsg(b.relative_odom);
  for (int i = 0; i < 6; ++i) m.odom_sigma[i] = static_cast<float>(b.odom_sigma[i]);
  for (const Object& o : b.objects) m.objects.push_back(toMsg(o));
  m.num_objects = static_cast<int32_t>(m.objects.size());
  return m;
}

object_map_t objectMapMsg(std::int64_t utime, int robot, const std::vector<Object>& objects) {
  object_map_t m;
  m.utime = utime;
  m.robot = robot;
  m.frame_robot = robot;
  for (const Object& o : objects) m.objects.push_back(toMsg(o));
  m.num_objects = static_cast<int32_t>(m.objects.size());
  return m;
}

trajectory_t trajectoryMsg(std::int64_t utime, int robot, int frame_robot, const std::vector<TrajectoryPose>& poses) {
  trajectory_t m;
  m.utime = utime;
  m.robot = robot;
  m.frame_robot = frame_robot;
  for (const TrajectoryPose& p : poses) {
    m.keypose_seq.push_back(p.seq);
    m.pose_utime.push_back(p.utime);
    m.poses.push_back(toMsg(p.pose));
  }
  m.num_poses = static_cast<int32_t>(m.poses.size());
  return m;
}

}  // namespace slide
