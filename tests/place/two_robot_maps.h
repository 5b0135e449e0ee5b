#pragma once
// Two robots' maps of one place for the loop closer's tests: 70 mixed-class objects of robot 0
// (ids 0..69) and the same objects seen by robot 1 in its own frame (ids 100..169), and their
// object_map_t messages.
#include <random>
#include <utility>
#include <vector>

#include "msg/convert.h"
#include "slide/object_map_t.hpp"

namespace slide::testing {

// `T_0_1` maps robot 1's frame into robot 0's.
inline std::pair<std::vector<Object>, std::vector<Object>> twoRobotViews(const Pose& T_0_1) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 40);
  const int classes[] = {71, 10, 0, 1};
  std::vector<Object> own, peer;
  for (int i = 0; i < 70; ++i) {
    Object o;
    o.id = i;
    o.class_id = classes[i % 4];
    o.model = Ellipsoid{{u(rng), u(rng), 0.5}, 0.3, 1.0};
    own.push_back(o);
    Object p = transformObject(T_0_1.inverse(), o);
    p.id = 100 + i;
    peer.push_back(p);
  }
  return {own, peer};
}

// A map of `robot` in its own frame.
inline object_map_t mapMsg(int robot, const std::vector<Object>& objects) {
  object_map_t m;
  m.utime = 0;
  m.robot = m.frame_robot = robot;
  for (const Object& o : objects) m.objects.push_back(msg::toLcm(o));
  m.num_objects = static_cast<int32_t>(m.objects.size());
  return m;
}

}  // namespace slide::testing
