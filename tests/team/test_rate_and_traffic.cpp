#include <gtest/gtest.h>

#include "team/bandwidth.h"
#include "team/rate_limiter.h"
#include "team/sim_network.h"
#include "team_test_util.h"

using namespace slide::team;
using namespace slide::team::testing;

TEST(RateLimiter, LongRunRateAndBurstAreRespected) {
  RateLimiter rl(1000, 300);
  double taken = 0;
  for (Micros t = 0; t <= 10000000; t += 10000)
    while (rl.tryTake(100, t)) taken += 100;
  EXPECT_LE(taken, 1000 * 10 + 300 + 100);
  EXPECT_GE(taken, 1000 * 10 - 200);
  RateLimiter big(1000, 300);
  EXPECT_TRUE(big.tryTake(5000, 0));  // larger than the burst: allowed when full, never stuck
  EXPECT_FALSE(big.tryTake(10, 1000));
  EXPECT_TRUE(big.tryTake(10, 6000000));
}

TEST(BandwidthMeter, SharesBroadcastsAndComputesRates) {
  BandwidthMeter m(0);
  m.sent({2, 3}, 100);
  m.sent({2}, 50);
  m.received(2, 400);
  EXPECT_DOUBLE_EQ(m.totalSent(), 150);
  EXPECT_DOUBLE_EQ(m.peers().at(2).bytes_sent, 100);
  EXPECT_DOUBLE_EQ(m.peers().at(3).bytes_sent, 50);
  const TrafficFigures f = m.figures(2, 2000000, 8, 40.0);
  EXPECT_DOUBLE_EQ(f.sent_bytes_per_s, 50);
  EXPECT_DOUBLE_EQ(f.received_bytes_per_s, 200);
  EXPECT_DOUBLE_EQ(f.received_per_landmark, 50);
  EXPECT_DOUBLE_EQ(f.received_per_metre, 10);
}

TEST(PeerSyncSim, RateLimitBoundsWhatEachRobotSends) {
  // A big backlog (60 bundles each) released at once must go out no faster than the limit.
  std::vector<SyncConfig> cfgs;
  for (int id : {1, 2}) {
    SyncConfig c = teamConfig(id, {1, 2});
    c.rate_limit_bytes_per_s = 1500;
    c.burst_bytes = 1000;
    cfgs.push_back(c);
  }
  SimNetwork net(cfgs, "", SimLinkModel{}, 3);
  std::mt19937 rng(4);
  for (int s = 0; s < 60; ++s)
    for (int i = 0; i < 2; ++i) ASSERT_FALSE(net.node(i).addOwnBundle(randomBundle(rng, i + 1, s), 0));
  net.run(5000000);
  const double limit = 2 * (1500.0 * 5 + 1000);  // two robots, 5 s
  EXPECT_LE(net.bytesSent(), limit * 1.05);
  EXPECT_GT(net.bytesSent(), limit * 0.6);       // and the limit is used, not starved
  EXPECT_LT(net.delivered(0).size(), 60u);       // so not everything could be delivered yet
  net.run(60000000);
  EXPECT_EQ(net.delivered(0).size(), 60u);
  EXPECT_EQ(net.delivered(1).size(), 60u);
}

TEST(SyncConfig, ShippedFileLoadsAndBadValuesNameTheKey) {
  const auto node = slide::ConfigNode::load(std::string(SLIDE_SOURCE_DIR) + "/config/peer_sync.yaml");
  const SyncConfig c = SyncConfig::fromConfig(node, 2);
  EXPECT_EQ(c.robot, 2);
  EXPECT_EQ(c.team.size(), 3u);
  EXPECT_LE(c.max_chunk_bytes, 1300u);  // one LCM datagram per chunk
  EXPECT_THROW(SyncConfig::fromConfig(node, 9), slide::ConfigError);  // not in the team
  try {
    SyncConfig::fromConfig(slide::ConfigNode::parse("team: [1]\nmax_chunk_bytes: lots\n", "t.yaml"), 1);
    FAIL() << "expected a ConfigError";
  } catch (const slide::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("max_chunk_bytes"), std::string::npos) << e.what();
  }
  // A key shared by the whole team is refused, with the reason.
  try {
    SyncConfig::fromConfig(slide::ConfigNode::parse("team: [1]\nteam_key: k\n", "t.yaml"), 1);
    FAIL() << "a shared team_key was accepted";
  } catch (const slide::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("team_key_file"), std::string::npos) << e.what();
  }
  for (const std::string bad : {"bundle_hold_s: -1\n", "bundle_hold_s: 100\n", "heartbeat_idle_factor: 0.5\n",
                                "heartbeat_idle_factor: 6\n"}) {  // 6 * 8 s beyond the 40 s peer timeout
    try {
      SyncConfig::fromConfig(slide::ConfigNode::parse("team: [1]\n" + bad, "t.yaml"), 1);
      FAIL() << "accepted " << bad;
    } catch (const slide::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(bad.substr(0, bad.find(':'))), std::string::npos) << e.what();
    }
  }
}

TEST(PeerSyncSim, IdleHeartbeatsBackOffAndComeBackWithNews) {
  std::vector<SyncConfig> cfgs = {teamConfig(1, {1, 2}), teamConfig(2, {1, 2})};  // 1 s period, 3 s timeout
  for (auto& c : cfgs) c.ack_delay_s = 2.0, c.bundle_hold_s = 0;  // heartbeats acknowledge
  bool cut = false;
  SimLinkModel link;
  link.link_up = [&cut](std::int32_t, std::int32_t, Micros) { return !cut; };
  SimNetwork net(cfgs, "", link, 3);
  std::size_t heartbeats[2] = {0, 0}, acks = 0;
  std::vector<Micros> receiver_heartbeats;
  net.on_send = [&](std::size_t from, const TeamMessage& m) {
    heartbeats[from] += std::holds_alternative<Heartbeat>(m);
    if (from == 1 && std::holds_alternative<Heartbeat>(m)) receiver_heartbeats.push_back(net.now());
    acks += std::holds_alternative<Ack>(m);
  };
  net.run(30000000);
  EXPECT_LE(heartbeats[0], 17u);  // every 2 s (heartbeat_idle_factor 2) instead of every second
  EXPECT_GE(heartbeats[0], 14u);
  EXPECT_TRUE(net.node(1).inReach(1, net.now()));
  // Own bundles every second, received in order: neither side hurries its heartbeats (the
  // receiver's idle heartbeats acknowledge them), and everything arrives.
  std::mt19937 rng(4);
  heartbeats[0] = heartbeats[1] = 0;
  int seq = 0;
  for (; seq < 10; ++seq) {
    ASSERT_FALSE(net.node(0).addOwnBundle(randomBundle(rng, 1, seq), net.now()));
    net.run(1000000);
  }
  EXPECT_LE(heartbeats[0], 6u);
  EXPECT_LE(heartbeats[1], 6u);
  EXPECT_EQ(acks, 0u);
  EXPECT_EQ(net.delivered(1).size(), 10u);
  // A bundle lost on the way leaves a gap at the receiver once the next one arrives: that is
  // news, so its next heartbeat goes one period after the previous (not the idle two), and the
  // sender fills the gap.
  cut = true;
  ASSERT_FALSE(net.node(0).addOwnBundle(randomBundle(rng, 1, seq++), net.now()));
  net.run(100000);
  cut = false;
  const Micros before_gap = receiver_heartbeats.back();
  ASSERT_FALSE(net.node(0).addOwnBundle(randomBundle(rng, 1, seq++), net.now()));
  net.run(100000);
  ASSERT_EQ(receiver_heartbeats.back(), before_gap) << "the test needs the gap seen between two heartbeats";
  net.run(2000000);
  const auto after = std::upper_bound(receiver_heartbeats.begin(), receiver_heartbeats.end(), before_gap);
  ASSERT_NE(after, receiver_heartbeats.end());
  EXPECT_LE(*after - before_gap, 1100000);
  net.run(2000000);
  EXPECT_EQ(net.delivered(1).size(), 12u);
  EXPECT_THROW(
      [] {
        SyncConfig c = teamConfig(1, {1, 2});
        c.heartbeat_idle_factor = 4;  // 4 s between heartbeats with a 3 s peer timeout
        c.validate();
      }(),
      std::invalid_argument);
}

TEST(PeerSyncSim, HeartbeatsAnnounceOwnBundlesOnceSent) {
  std::vector<SyncConfig> cfgs = {teamConfig(1, {1, 2}), teamConfig(2, {1, 2})};
  cfgs[0].bundle_hold_s = 3.0;  // own bundles wait for company
  SimNetwork net(cfgs, "", SimLinkModel{}, 5);
  std::vector<std::pair<Micros, Heartbeat>> sent;  // robot 1's heartbeats
  std::vector<Micros> chunk_times;
  net.on_send = [&](std::size_t from, const TeamMessage& m) {
    if (from != 0) return;
    if (auto* h = std::get_if<Heartbeat>(&m)) sent.emplace_back(net.now(), *h);
    if (std::holds_alternative<Chunk>(m)) chunk_times.push_back(net.now());
  };
  net.run(3000000);  // both in reach
  std::mt19937 rng(6);
  for (int seq = 0; seq < 2; ++seq) ASSERT_FALSE(net.node(0).addOwnBundle(randomBundle(rng, 1, seq), net.now()));
  sent.clear();
  net.run(6000000);
  ASSERT_EQ(chunk_times.size(), 1u);  // both bundles in one chunk, after the hold
  bool before = false, after = false;
  for (const auto& [t, h] : sent) {
    const bool announces = h.held.count(1) > 0;
    if (t < chunk_times[0]) {
      before = true;
      EXPECT_FALSE(announces) << "announced at " << t << " before the send";
    } else {
      after = true;
      EXPECT_TRUE(announces && h.held.at(1).count() == 2);
    }
  }
  EXPECT_TRUE(before);
  EXPECT_TRUE(after);
  EXPECT_EQ(net.delivered(1).size(), 2u);
}
