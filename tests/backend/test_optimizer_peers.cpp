// The optimizer's store of peers' bundles (issue 16, findings 2 and 8): objects beyond any
// sensor's range are dropped before they can reach association, also when the bundle was held
// and journalled before its robot's transform came and is replayed after a restart; the
// number of peers and of bundles held per peer is bounded, and what is refused is counted.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "msg/convert.h"
#include "optimizer_node.h"
#include "scenario_messages.h"
#include "slide/optimizer_status_t.hpp"

using namespace slide;
using slide::testing::RawMessage;

namespace {

std::string tempDir() {
  const auto dir = std::filesystem::temp_directory_path() / ("slide_backend_peers_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

void feed(OptimizerNode& node, const RawMessage& m) {
  node.handle(m.channel, m.bytes.data(), static_cast<int>(m.bytes.size()));
}

keypose_bundle_t decoded(const RawMessage& m) {
  keypose_bundle_t b;
  EXPECT_GE(b.decode(m.bytes.data(), 0, static_cast<int>(m.bytes.size())), 0);
  return b;
}

}  // namespace

TEST(OptimizerPeers, FarObjectInAHeldPeerBundleIsDroppedAlsoAfterReplay) {
  std::vector<RawMessage> msgs = slide::testing::twoRobotMessages();
  // Robot 1's third bundle gets an extra copy of its first object 1e5 m away (1e7 m made the
  // association scan ~1e10 grid cells at the merge: a hang, after every restart).
  std::size_t peer_seen = 0, far_at = 0;
  for (std::size_t i = 0; i < msgs.size() && !far_at; ++i)
    if (msgs[i].channel == "PEER_BUNDLE" && ++peer_seen == 3) far_at = i;
  std::vector<std::string> warnings;
  KeyPoseBundle b = msg::fromLcm(decoded(msgs[far_at]), &warnings);
  ASSERT_FALSE(b.objects.empty());
  b.objects.push_back(transformObject(poseFromXyzYaw(1e5, 0, 0, 0), b.objects[0]));
  msgs[far_at].bytes = slide::testing::encodeMsg(msg::toLcm(b));
  std::size_t merge_at = 0;
  for (std::size_t i = 0; i < msgs.size() && !merge_at; ++i)
    if (msgs[i].channel == "LOOP_CLOSURE") merge_at = i;
  ASSERT_GT(merge_at, far_at);

  const std::string dir = tempDir(), journal = dir + "/optimizer.journal";
  const ClassTable classes = ClassTable::loadDefault();
  {
    OptimizerNode first(backend::BackendConfig{}, classes, 0, {}, {});
    first.openJournal(journal);
    for (std::size_t i = 0; i < merge_at; ++i) feed(first, msgs[i]);
    EXPECT_EQ(first.optimizer().rejected(), 0);  // the bundle is held (its other objects count)
  }
  OptimizerNode second(backend::BackendConfig{}, classes, 0, {}, {});
  EXPECT_EQ(second.openJournal(journal), static_cast<int>(merge_at));
  for (std::size_t i = merge_at; i < msgs.size(); ++i) feed(second, msgs[i]);
  EXPECT_TRUE(second.optimizer().merged(1));
  for (const Object& o : second.optimizer().landmarks(false)) EXPECT_LT(o.position().norm(), 1000.0) << o.id;
  std::filesystem::remove_all(dir);
}

TEST(OptimizerPeers, PeersAndHeldBundlesAreBoundedAndCounted) {
  backend::BackendConfig cfg;
  cfg.max_peers = 2;
  cfg.max_held_bundles = 5;
  std::vector<std::vector<uint8_t>> status;
  OptimizerNode node(cfg, ClassTable::loadDefault(), 0, {},
                     [&](const std::string& channel, const std::vector<uint8_t>& bytes) {
                       if (channel == "OPTIMIZER_STATUS") status.push_back(bytes);
                       return true;
                     });
  const std::vector<RawMessage> msgs = slide::testing::twoRobotMessages();
  std::vector<KeyPoseBundle> peer;
  for (const auto& m : msgs)
    if (m.channel == "PEER_BUNDLE") {
      std::vector<std::string> w;
      peer.push_back(msg::fromLcm(decoded(m), &w));
    }
  ASSERT_GE(peer.size(), 8u);
  // 100 robot ids, 8 bundles each: 2 peers of 5 held bundles are kept.
  for (int id = 1; id <= 100; ++id)
    for (int k = 0; k < 8; ++k) {
      KeyPoseBundle b = peer[static_cast<std::size_t>(k)];
      b.robot = id;
      const auto bytes = slide::testing::encodeMsg(msg::toLcm(b));
      node.handle("PEER_BUNDLE", bytes.data(), static_cast<int>(bytes.size()));
    }
  EXPECT_EQ(node.optimizer().numHeld(), 10);
  EXPECT_EQ(node.optimizer().rejected(), 800 - 10);
  EXPECT_EQ(node.optimizer().rejections().at("too many peers"), 98 * 8);
  EXPECT_EQ(node.optimizer().rejections().at("peer store full"), 2 * 3);
  ASSERT_FALSE(status.empty());
  optimizer_status_t s;
  ASSERT_GE(s.decode(status.back().data(), 0, static_cast<int>(status.back().size())), 0);
  EXPECT_EQ(s.rejected_inputs, 790);
}

TEST(OptimizerPeers, OwnMapHoldsOnlyLandmarksTheRobotObservedItself) {
  // Robot 0 drives a third of the room, robot 1 on around it: after the merge the merged map
  // holds robot 1's landmarks too, the own map (place recognition's and the team's input) only
  // robot 0's.
  std::map<std::string, object_map_t> last;
  OptimizerNode node(backend::BackendConfig{}, ClassTable::loadDefault(), 0, {},
                     [&](const std::string& channel, const std::vector<uint8_t>& bytes) {
                       object_map_t m;
                       if (m.decode(bytes.data(), 0, static_cast<int>(bytes.size())) >= 0) last[channel] = m;
                       return true;
                     });
  OptimizerNode alone(backend::BackendConfig{}, ClassTable::loadDefault(), 0, {}, {});
  for (const auto& m : slide::testing::twoRobotMessages(45, 25, 130)) {
    feed(node, m);
    if (m.channel == "KEYPOSE_BUNDLE") feed(alone, m);
  }
  ASSERT_TRUE(node.optimizer().merged(1));
  const object_map_t& merged = last.at("OBJECT_MAP");
  const object_map_t& own = last.at("OWN_MAP");
  const std::vector<Object> truth_own = alone.optimizer().landmarks();
  EXPECT_GT(merged.num_objects, own.num_objects + 5) << "robot 1's own stretch adds landmarks to the merged map";
  EXPECT_NEAR(own.num_objects, static_cast<int>(truth_own.size()), 3);
  // Every own-map landmark is one robot 0 maps on its own (same class, within 0.5 m).
  for (const object_t& o : own.objects) {
    const Object mine = msg::fromLcm(o);
    const bool found = std::any_of(truth_own.begin(), truth_own.end(), [&](const Object& t) {
      return t.class_id == mine.class_id && (t.position() - mine.position()).norm() < 0.5;
    });
    EXPECT_TRUE(found) << "own map landmark " << o.id << " is not one robot 0 observed";
  }
}
