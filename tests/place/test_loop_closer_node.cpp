// The loop closer's node without a bus: maps in as decoded messages, loop closures out through
// the injected publisher; hostile maps are dropped and counted.
#include <gtest/gtest.h>

#include <cmath>

#include "loop_closer_node.h"
#include "slide/loop_closure_t.hpp"
#include "two_robot_maps.h"

using namespace slide;
using slide::testing::mapMsg;
using slide::testing::twoRobotViews;

namespace {
struct Sent {
  std::vector<std::pair<std::string, loop_closure_t>> closures;
  msg::Publisher publisher() {
    return [this](const std::string& channel, const std::vector<uint8_t>& bytes) {
      loop_closure_t m;
      EXPECT_EQ(m.decode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
      closures.emplace_back(channel, m);
      return true;
    };
  }
};

place::LoopCloserParams params() {
  place::LoopCloserParams p;
  p.robot = 0;
  p.inter_period_s = 0.5;
  p.stagger_s = 0;
  return p;
}
}  // namespace

TEST(LoopCloserNode, PublishesTheTransformBetweenTwoRobotsMapsOnceConfirmed) {
  const Pose T_0_1 = poseFromXyzYaw(-15, 22, 0.5, -2.0);
  const auto [own, peer] = twoRobotViews(T_0_1);
  Sent sent;
  LoopCloserNode node(params(), {}, sent.publisher());
  double t = 0;
  for (; t < 10 && sent.closures.empty(); t += 0.6) {
    node.onMap("OBJECT_MAP", mapMsg(0, own), t);
    node.onMap("PEER_MAP", mapMsg(1, peer), t);
    node.poll(t);
  }
  ASSERT_EQ(sent.closures.size(), 1u) << node.closer().lastReason();
  EXPECT_EQ(node.published(), 1);
  const auto& [channel, lc] = sent.closures.front();
  EXPECT_EQ(channel, "LOOP_CLOSURE");
  EXPECT_EQ(lc.robot_a, 0);
  EXPECT_EQ(lc.robot_b, 1);
  EXPECT_EQ(lc.method, loop_closure_t::SLIDEGRAPH);
  EXPECT_NEAR(lc.x, -15, 1e-3);
  EXPECT_NEAR(lc.y, 22, 1e-3);
  EXPECT_NEAR(lc.yaw, -2.0, 1e-4);
  ASSERT_EQ(lc.num_inliers, 70);
  for (int i = 0; i < lc.num_inliers; ++i) EXPECT_EQ(lc.inliers_b[i], lc.inliers_a[i] + 100);
}

TEST(LoopCloserNode, HostileMapsAreDroppedAndCounted) {
  const auto [own, peer] = twoRobotViews(poseFromXyzYaw(3, 4, 0, 0.5));
  place::LoopCloserParams p = params();
  p.max_map_objects = 60;
  Sent sent;
  LoopCloserNode node(p, {}, sent.publisher());
  std::vector<Object> bad = {own[0], own[1], own[2]};
  std::get<Ellipsoid>(bad[0].model).centroid.x() = std::nan("");
  std::get<Ellipsoid>(bad[1].model).centroid.y() = 1e7;  // beyond any robot's range
  node.onMap("PEER_MAP", mapMsg(1, bad), 0);
  EXPECT_EQ(node.droppedObjects(), 2);
  node.onMap("PEER_MAP", mapMsg(1, peer), 0);  // 70 objects: over the cap
  EXPECT_EQ(node.closer().counts().oversized_maps, 1);
  object_map_t elsewhere = mapMsg(1, peer);
  elsewhere.frame_robot = 0;  // a peer's map in our frame: not a map to match
  node.onMap("PEER_MAP", elsewhere, 0);
  EXPECT_EQ(node.closer().counts().oversized_maps, 1);
  EXPECT_EQ(node.droppedInputs(), 3);
  for (double t = 0; t < 3; t += 0.6) node.poll(t);
  EXPECT_TRUE(sent.closures.empty());
}
