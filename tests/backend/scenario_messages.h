#pragma once
// LCM input messages for the optimizer node made from a two-robot indoor scenario: robot 0's
// bundles, robot 1's (peer) bundles interleaved, the inter-robot transform half-way and an
// intra-robot loop closure near the end.
#include <algorithm>
#include <string>
#include <vector>

#include "bundle_messages.h"
#include "graph_scenario/scenario.h"
#include "slide/loop_closure_t.hpp"

namespace slide::testing {

struct RawMessage {
  std::string channel;
  std::vector<uint8_t> bytes;
};

template <typename M>
std::vector<uint8_t> encodeMsg(const M& m) {
  std::vector<uint8_t> buf(m.getEncodedSize());
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

// Robot 0 drives the indoor scenario's poses [0, a_end), robot 1 [b_begin, b_end).
inline std::vector<RawMessage> twoRobotMessages(int a_end = 80, int b_begin = 50, int b_end = 130) {
  graph_scenario::GraphScenario s = graph_scenario::makeIndoorScenario(6);
  const std::vector<Pose> path = s.robots[0].truth;
  std::mt19937 rng(3);
  const graph_scenario::ScenarioRobot a =
      graph_scenario::simulateRobot(0, {path.begin(), path.begin() + a_end}, s.landmarks, s.noise, rng);
  const graph_scenario::ScenarioRobot b = graph_scenario::simulateRobot(
      1, {path.begin() + b_begin, path.begin() + b_end}, s.landmarks, s.noise, rng, 7000000);
  std::vector<RawMessage> out;
  for (std::size_t k = 0; k < std::max(a.bundles.size(), b.bundles.size()); ++k) {
    if (k < a.bundles.size()) out.push_back({"KEYPOSE_BUNDLE", encodeMsg(msg::toLcm(a.bundles[k]))});
    if (k < b.bundles.size()) out.push_back({"PEER_BUNDLE", encodeMsg(msg::toLcm(b.bundles[k]))});
    if (k == 40) {
      const Pose T = a.truth[0].inverse() * b.truth[0];
      loop_closure_t lc{};
      lc.robot_a = 0;
      lc.robot_b = 1;
      lc.x = T.translation().x();
      lc.y = T.translation().y();
      lc.z = T.translation().z();
      lc.yaw = yawOf(T.linear());
      lc.num_inliers = 0;
      out.push_back({"LOOP_CLOSURE", encodeMsg(lc)});
    }
    if (k == 70 && a.truth.size() > 70) {
      const Pose T = a.truth[5].inverse() * a.truth[70];
      loop_closure_t lc{};
      lc.robot_a = lc.robot_b = 0;
      lc.keypose_a = 5;
      lc.keypose_b = 70;
      lc.x = T.translation().x();
      lc.y = T.translation().y();
      lc.z = T.translation().z();
      lc.yaw = yawOf(T.linear());
      out.push_back({"LOOP_CLOSURE", encodeMsg(lc)});
    }
  }
  return out;
}

}  // namespace slide::testing
