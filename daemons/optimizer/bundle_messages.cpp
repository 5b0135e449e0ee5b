#include "bundle_messages.h"

#include "msg/convert.h"

namespace slide {

object_map_t objectMapMsg(std::int64_t utime, int robot, const std::vector<Object>& objects) {
  object_map_t m;
  m.utime = utime;
  m.robot = robot;
  m.frame_robot = robot;
  for (const Object& o : objects) m.objects.push_back(msg::toLcm(o));
  m.num_objects = static_cast<int32_t>(m.objects.size());
  return m;
}

trajectory_t trajectoryMsg(std::int64_t utime, int robot, int frame_robot,
                           const std::vector<backend::TrajectoryPose>& poses) {
  trajectory_t m;
  m.utime = utime;
  m.robot = robot;
  m.frame_robot = frame_robot;
  for (const backend::TrajectoryPose& p : poses) {
    m.keypose_seq.push_back(p.seq);
    m.pose_utime.push_back(p.utime);
    m.poses.push_back(msg::toLcm(p.pose));
  }
  m.num_poses = static_cast<int32_t>(m.poses.size());
  return m;
}

}  // namespace slide
