// Peer sync's node without a bus: two robots' nodes wired to each other through their injected
// publishers. An own bundle of robot 0 reaches robot 1's robot bus once, as PEER_BUNDLE, and its
// map as PEER_MAP; malformed input on either bus is counted, never fatal.
#include <gtest/gtest.h>

#include <deque>

#include "peer_sync_node.h"
#include "slide/keypose_bundle_t.hpp"
#include "slide/object_map_t.hpp"
#include "slide/peer_sync_status_t.hpp"
#include "team_msg.h"
#include "team_test_util.h"

using namespace slide;
using namespace slide::team;
using namespace slide::team::testing;

namespace {
constexpr Micros kStep = 100000;  // 0.1 s

struct Message {
  std::string channel;
  std::vector<uint8_t> bytes;
};

// One robot: the engine, its node, and what the node published on each bus.
struct Robot {
  explicit Robot(std::int32_t id) : engine(config(id), "", 0) {}
  static SyncConfig config(std::int32_t id) {
    SyncConfig c = teamConfig(id, {0, 1});
    c.bundle_hold_s = 0;
    c.map_period_s = 1;
    return c;
  }
  PeerSyncNode engine;
  std::vector<Message> robot_bus;
  std::deque<Message> team_bus;
  std::vector<std::pair<std::string, std::string>> undecodable;
  PeerSyncDaemon node{engine, PeerSyncChannels{}, 4,
                      [this](const std::string& c, const std::vector<uint8_t>& b) {
                        robot_bus.push_back({c, b});
                        return true;
                      },
                      [this](const std::string& c, const std::vector<uint8_t>& b) {
                        team_bus.push_back({c, b});
                        return true;
                      },
                      {[this](const std::string& c, const std::string& why) { undecodable.emplace_back(c, why); }, {}}};
};

// Steps both robots for `seconds`, carrying each one's team traffic to the other.
void run(Robot& a, Robot& b, Micros& now, double seconds) {
  for (Micros end = now + static_cast<Micros>(seconds * 1e6); now < end; now += kStep) {
    for (auto [from, to] : {std::pair{&a, &b}, std::pair{&b, &a}}) {
      from->node.step(now);
      for (; !from->team_bus.empty(); from->team_bus.pop_front()) {
        const Message& m = from->team_bus.front();
        to->node.onTeam(m.channel, m.bytes.data(), m.bytes.size(), now);
      }
    }
  }
}

std::vector<Message> on(const Robot& r, const std::string& channel) {
  std::vector<Message> out;
  for (const Message& m : r.robot_bus)
    if (m.channel == channel) out.push_back(m);
  return out;
}

// The one message `r` published on `channel`, decoded (nullopt, and a failure, otherwise).
template <typename M>
std::optional<M> theOne(const Robot& r, const std::string& channel) {
  const auto all = on(r, channel);
  EXPECT_EQ(all.size(), 1u) << channel;
  if (all.size() != 1) return std::nullopt;
  auto m = decodeLcm<M>(all[0].bytes.data(), all[0].bytes.size());
  EXPECT_TRUE(m) << channel << ": undecodable";
  return m;
}
}  // namespace

TEST(PeerSyncNode, OwnBundleAndMapReachThePeersRobotBusOnce) {
  Robot a(0), b(1);
  Micros now = 0;
  run(a, b, now, 2);  // they hear each other
  std::mt19937 rng(5);
  const KeyPoseBundle sent = randomBundle(rng, 0, 0);
  const std::vector<uint8_t> bytes = msg::encodeLcm(msg::toLcm(sent));
  a.node.onOwnBundle("KEYPOSE_BUNDLE", bytes.data(), bytes.size(), now);
  SharedMap map;
  map.robot = map.frame_robot = 0;
  for (int i = 0; i < 5; ++i) map.objects.push_back(randomObject(rng, i));
  const std::vector<uint8_t> map_bytes = msg::encodeLcm(toLcm(map));
  a.node.onOwnMap("OBJECT_MAP", map_bytes.data(), map_bytes.size(), now);
  run(a, b, now, 5);

  const auto got = theOne<keypose_bundle_t>(b, "PEER_BUNDLE");
  ASSERT_TRUE(got);
  std::string why;
  const auto delivered = acceptBundle(*got, &why);
  ASSERT_TRUE(delivered) << why;
  EXPECT_TRUE(bundlesNear(*delivered, roundTrip(sent), 1e-4));
  const auto got_map = theOne<object_map_t>(b, "PEER_MAP");
  ASSERT_TRUE(got_map);
  EXPECT_EQ(got_map->robot, 0);
  EXPECT_EQ(got_map->num_objects, 5);
  EXPECT_TRUE(on(a, "PEER_BUNDLE").empty());  // its own bundle is not delivered back

  b.node.logStats(now);  // the status on the robot bus
  const auto st = theOne<peer_sync_status_t>(b, "PEER_SYNC_STATUS");
  ASSERT_TRUE(st);
  EXPECT_EQ(st->robot, 1);
  EXPECT_EQ(st->held_bundles, 1);
}

TEST(PeerSyncNode, MalformedInputIsCountedNotFatal) {
  Robot a(0), b(1);
  const std::vector<uint8_t> junk = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  a.node.onOwnBundle("KEYPOSE_BUNDLE", junk.data(), junk.size(), 0);
  a.node.onOwnMap("OBJECT_MAP", junk.data(), junk.size(), 0);
  ASSERT_EQ(a.undecodable.size(), 2u);
  EXPECT_EQ(a.undecodable[0].first, "KEYPOSE_BUNDLE");
  EXPECT_EQ(a.undecodable[1].first, "OBJECT_MAP");
  for (const char* channel : {"TEAM_HEARTBEAT", "TEAM_CHUNK", "TEAM_ACK"})
    a.node.onTeam(channel, junk.data(), junk.size(), 0);
  EXPECT_EQ(a.engine.dropped(Drop::Malformed), 3u);
  a.node.onTeam("SOMETHING_ELSE", junk.data(), junk.size(), 0);  // not a team channel: ignored
  EXPECT_EQ(a.engine.dropped(Drop::Malformed), 3u);
  Micros now = 0;
  run(a, b, now, 1);  // still working
  EXPECT_EQ(a.engine.db().size(), 0u);
}
