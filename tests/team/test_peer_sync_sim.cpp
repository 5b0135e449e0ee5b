// Property tests of the bookmark protocol on a simulated team network: seeded loss,
// duplication, reordering, link cuts and restarts; every bundle delivered exactly once and in
// per-origin order, identical to what its origin recorded.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "team/bundle_pack.h"
#include "team/codec.h"
#include "team/sim_network.h"
#include "team_test_util.h"

using namespace slide;
using namespace slide::team;
using namespace slide::team::testing;
namespace fs = std::filesystem;

namespace {

constexpr Micros kSecond = 1000000;
const std::vector<std::int32_t> kIds = {3, 7, 11};
const std::vector<std::int32_t> kTeam = {3, 7, 11, 20};  // 20: a team member with no node (attacker)

struct Scenario {
  std::uint64_t seed = 1;
  int bundles = 30;
  double loss = 0, duplicate = 0, jitter_s = 0;
  bool cuts = false;      // each link down half the time
  bool restarts = false;  // random restarts of any node
  bool line = false;      // robots 0 and 2 never hear each other
  bool default_timing = false;  // SyncConfig defaults instead of the quick test timings
  bool thinning = false;        // own observations thinned (the default policy)
};

std::string freshDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("slide_team_sim_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

class SimRun {
 public:
  SimRun(const Scenario& s, const std::string& name) : s_(s), dir_(freshDir(name)), rng_(static_cast<unsigned>(s.seed)) {
    std::vector<SyncConfig> cfgs;
    for (auto id : kIds) {
      cfgs.push_back(teamConfig(id, kTeam));
      if (s.default_timing) {
        SyncConfig d;
        d.robot = id;
        d.team = kTeam;
        d.pair_keys = cfgs.back().pair_keys;
        d.thin_observations = false;
        cfgs.back() = d;
      }
      cfgs.back().thin_observations = s.thinning;
    }
    SimLinkModel link;
    link.loss = s.loss;
    link.duplicate = s.duplicate;
    link.jitter_s = s.jitter_s;
    const bool cuts = s.cuts, line = s.line;
    link.link_up = [this, cuts, line](std::int32_t a, std::int32_t b, Micros t) {
      if (line && ((a == kIds[0] && b == kIds[2]) || (a == kIds[2] && b == kIds[0]))) return false;
      if (!cuts || healed_) return true;
      // Each pair has its own 8 s period, up for the first half (phase differs per pair).
      const Micros period = 8 * kSecond, phase = (a * 7 + b * 7) % 8 * kSecond;
      return (t + phase) % period < period / 2;
    };
    net_ = std::make_unique<SimNetwork>(cfgs, dir_, link, s.seed);
    sent_.resize(kIds.size());
  }
  ~SimRun() { fs::remove_all(dir_); }

  void produce() {
    for (int k = 0; k < s_.bundles; ++k) {
      for (std::size_t i = 0; i < kIds.size(); ++i) {
        const std::int32_t seq = 100 * static_cast<std::int32_t>(i) + k;  // origins start at different seqs
        KeyPoseBundle b = s_.thinning ? trackerBundle(i, seq) : randomBundle(rng_, kIds[i], seq);
        ASSERT_FALSE(net_->node(i).addOwnBundle(b, net_->now()));
        b.first = k == 0;
        sent_[i].push_back(s_.thinning ? shared(i, b) : roundTrip(b));
      }
      net_->run(kSecond);
      if (s_.restarts && rng_() % 4 == 0) net_->restart(rng_() % kIds.size());
    }
  }

  // Heals the links and runs until everyone holds everything (or `limit` passes).
  void converge(Micros limit) {
    healed_ = true;
    const std::size_t total = kIds.size() * static_cast<std::size_t>(s_.bundles);
    for (Micros t = 0; t < limit; t += kSecond) {
      bool done = true;
      for (std::size_t i = 0; i < kIds.size(); ++i)
        done = done && net_->node(i).db().size() == total && net_->delivered(i).size() == total - s_.bundles;
      if (done) return;
      net_->run(kSecond);
    }
  }

  void expectExactlyOnceInOrder() {
    for (std::size_t i = 0; i < kIds.size(); ++i) {
      const auto& got = net_->deliveredBundles(i);
      EXPECT_EQ(got.size(), (kIds.size() - 1) * static_cast<std::size_t>(s_.bundles)) << "robot " << kIds[i];
      for (std::size_t j = 0; j < kIds.size(); ++j) {
        std::vector<KeyPoseBundle> from_j;
        for (const auto& b : got)
          if (b.robot == kIds[j]) from_j.push_back(b);
        if (j == i) {
          EXPECT_TRUE(from_j.empty()) << "own bundles are not delivered back";
          continue;
        }
        ASSERT_EQ(from_j.size(), sent_[j].size()) << "robot " << kIds[i] << " from " << kIds[j];
        for (std::size_t k = 0; k < from_j.size(); ++k) {
          ASSERT_EQ(from_j[k].seq, sent_[j][k].seq) << "order at robot " << kIds[i];
          EXPECT_TRUE(bundlesNear(from_j[k], sent_[j][k])) << "content";
          // The stored bytes are what the origin shared, bit for bit, whoever relayed them.
          EXPECT_EQ(net_->node(i).db().get(kIds[j], from_j[k].seq)->data,
                    *net_->node(j).wirePayload(kIds[j], from_j[k].seq));
        }
      }
    }
  }

  SimNetwork& net() { return *net_; }
  std::size_t thinnedOut() const { return thinned_out_; }

 private:
  // Odometry composed from the steps (chained encodings) and trunks seen over several key poses.
  KeyPoseBundle trackerBundle(std::size_t i, std::int32_t seq) {
    KeyPoseBundle b = randomBundle(rng_, kIds[i], seq, 0);
    b.relative_odom = poseFromXyzYaw(1.4, 0.01 * (rng_() % 5), 0, 0.02 * (static_cast<int>(rng_() % 11) - 5));
    odom_[i] = odom_[i] * b.relative_odom;
    b.odom_pose = odom_[i];
    for (int j = 0; j < 8; ++j) {
      Object o;
      o.id = (seq + j) / 8 * 8 + j;
      o.class_id = 71;
      o.num_observations = seq % 8 + 1;
      o.model = Cylinder{{4.0 + 0.01 * (rng_() % 30), j - 4.0, 0}, Eigen::Vector3d::UnitZ(), 0.2, 5.0};
      b.objects.push_back(o);
    }
    return b;
  }

  // What receivers get of an own bundle: the origin's full encoding decoded, thinned, encoded
  // again and decoded (each chained to the previous bundle as decoded).
  KeyPoseBundle shared(std::size_t i, const KeyPoseBundle& b) {
    const BundleContext* previous = context_[i] ? &*context_[i] : nullptr;
    std::string err;
    const Bytes full_data = encodeBundle(b, previous);
    const KeyPoseBundle full = *decodeBundle(full_data, b.robot, b.seq, &err, previous);
    const BundleDetail detail = s_.thinning ? BundleDetail::Team : BundleDetail::Full;
    const KeyPoseBundle out =
        *decodeBundle(encodeBundle(thinning_[i].thin(full), previous, detail), b.robot, b.seq, &err, previous);
    context_[i] = BundleContext::of(full, chainedBundle(full_data) ? previous : nullptr);
    thinned_out_ += full.objects.size() - out.objects.size();
    return out;
  }

  Scenario s_;
  std::string dir_;
  std::mt19937 rng_;
  bool healed_ = false;
  std::unique_ptr<SimNetwork> net_;
  std::vector<std::vector<KeyPoseBundle>> sent_;
  std::vector<ObservationThinning> thinning_ =
      std::vector<ObservationThinning>(kIds.size(), ObservationThinning(ThinningPolicy{}));
  std::vector<Pose> odom_ = std::vector<Pose>(kIds.size(), Pose::Identity());
  std::vector<std::optional<BundleContext>> context_ = std::vector<std::optional<BundleContext>>(kIds.size());
  std::size_t thinned_out_ = 0;
};

}  // namespace

class PeerSyncTiming : public ::testing::TestWithParam<bool> {};
INSTANTIATE_TEST_SUITE_P(QuickAndDefault, PeerSyncTiming, ::testing::Values(false, true));

TEST_P(PeerSyncTiming, LosslessDeliversEverythingOnceAndSendsEachBundleOnce) {
  Scenario s;
  s.default_timing = GetParam();
  SimRun run(s, std::string("lossless") + (s.default_timing ? "_default" : ""));
  std::size_t bundles_sent = 0, bundle_chunks = 0;
  run.net().on_send = [&](std::size_t, const TeamMessage& m) {
    auto* c = std::get_if<Chunk>(&m);
    if (!c || c->kind != ChunkKind::Bundle) return;
    ++bundle_chunks;
    std::string err;
    bundles_sent += unpackBundles(c->data, &err)->size();  // (small bundles: one chunk each pack)
  };
  run.produce();
  run.converge(30 * kSecond);
  run.expectExactlyOnceInOrder();
  // Multicast and overhearing: each bundle goes on the medium once, not once per peer, and
  // bundles produced within bundle_hold_s share a chunk.
  EXPECT_EQ(bundles_sent, 3u * s.bundles);
  EXPECT_LT(bundle_chunks, bundles_sent / 2);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(run.net().node(i).dropped(Drop::BadMac), 0u);
    EXPECT_EQ(run.net().node(i).dropped(Drop::Replay), 0u);
  }
}

namespace {
// 30% loss, 20% duplication, reordering, links cut half the time and every daemon restarted:
// every bundle arrives exactly once and in per-origin order. Returns the last run's count of
// observations kept home by thinning.
std::size_t expectDeliveryUnderAbuse(std::uint64_t seeds, bool thinning, const std::string& tag) {
  std::size_t thinned_out = 0;
  for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
    SCOPED_TRACE(tag + " seed " + std::to_string(seed));
    Scenario s;
    s.seed = seed;
    s.loss = 0.3;
    s.duplicate = 0.2;
    s.jitter_s = 0.4;
    s.cuts = true;
    s.restarts = true;
    s.thinning = thinning;
    s.bundles = 25;
    SimRun run(s, tag + std::to_string(seed));
    run.produce();
    run.converge(120 * kSecond);
    run.expectExactlyOnceInOrder();
    thinned_out = run.thinnedOut();
  }
  return thinned_out;
}
}  // namespace

TEST(PeerSyncSim, RandomLossDuplicationReorderingCutsAndRestarts) { expectDeliveryUnderAbuse(6, false, "lossy"); }

TEST(PeerSyncSim, ThinnedStreamsUnderLossDuplicationReorderingCutsAndRestarts) {
  // Most of the 8 trunks per key pose stay home.
  EXPECT_GT(expectDeliveryUnderAbuse(3, true, "thinned"), 3u * 25u);
}

TEST(PeerSyncSim, RelayMergesRobotsThatNeverMeet) {
  Scenario s;
  s.line = true;
  s.loss = 0.1;
  s.seed = 42;
  SimRun run(s, "line");
  run.produce();
  run.converge(60 * kSecond);
  run.expectExactlyOnceInOrder();
}

TEST(PeerSyncSim, ReplayTamperForgeryAndBadInputAreDroppedAndCounted) {
  Scenario s;
  s.bundles = 10;
  SimRun run(s, "attack");
  std::vector<TeamMessage> captured;
  run.net().on_send = [&](std::size_t from, const TeamMessage& m) {
    if (from == 0) captured.push_back(m);
  };
  run.produce();
  run.converge(20 * kSecond);
  run.net().on_send = nullptr;
  PeerSyncNode& victim = run.net().node(1);
  const std::size_t held = victim.db().size();
  const auto before = victim.drops();
  auto delta = [&](Drop d) { return victim.dropped(d) - before[static_cast<int>(d)]; };

  // Replays of everything robot 0 sent.
  for (const auto& m : captured) run.net().inject(0, m);
  run.net().run(kSecond);
  EXPECT_GE(delta(Drop::Replay), captured.size());

  const MessageAuth auth = authOf(20, kTeam), wrong = authOf(20, kTeam, "not-the-key");
  Chunk c;
  c.sender = 20;
  c.receiver = -1;
  c.counter = 1000;
  c.origin = 3;
  c.seq = 5;
  std::mt19937 rng(1);
  const Bytes forged = encodeBundle(randomBundle(rng, 3, 5));
  c.data = packBundles({&forged});
  // Tampered: signed, then changed.
  Chunk t = c;
  auth.sign(t);
  t.data[3] ^= 1;
  run.net().inject(2, t);
  // Wrong key.
  Chunk w = c;
  wrong.sign(w);
  run.net().inject(2, w);
  // Unknown sender with the right key.
  Chunk u = c;
  u.sender = 99;
  auth.sign(u);
  run.net().inject(2, u);
  // Robot 11 speaking for robot 3: it holds the key of pair {3, 11}, not that of {3, 7}.
  const PairKeys own = derivePairKeys("team-secret", kIds[2], kTeam);
  const MessageAuth impostor(kIds[0], kTeam, {{kIds[1], own.at(kIds[1])}, {kIds[2], own.at(kIds[0])}, {20, own.at(20)}});
  Chunk f = c;
  f.sender = kIds[0];
  f.counter = SimNetwork::kSimEpoch + 3600 * kSecond / 2;
  impostor.sign(f);
  EXPECT_TRUE(authOf(kIds[2], kTeam).verify(f));  // what it could fool is itself only
  run.net().inject(2, f);
  run.net().run(kSecond);
  EXPECT_EQ(delta(Drop::BadMac), 3u);
  EXPECT_EQ(delta(Drop::UnknownSender), 1u);

  // A team member (valid key) sending bad content: unknown origin, garbage, jumps, and an
  // attempt to overwrite a held bundle with different content.
  std::int64_t counter = 2000;
  auto send = [&](Chunk m) {
    m.counter = ++counter;
    auth.sign(m);
    run.net().inject(2, m);
  };
  Chunk x = c;
  x.origin = 55;
  send(x);
  x = c;
  x.data = {1, 2, 3};
  x.seq = 900;  // not held: would be stored if it decoded
  send(x);
  x = c;
  x.seq = 5 + 1000000;
  send(x);
  x = c;
  x.seq = 5;  // held already: a different bundle under the same id must not replace it
  const Bytes stored = victim.db().get(3, 5)->data;
  send(x);
  x = c;
  x.seq = -4;
  send(x);
  x = c;
  x.chunk_index = 3;
  x.num_chunks = 2;
  send(x);
  run.net().run(kSecond);
  EXPECT_EQ(delta(Drop::UnknownOrigin), 1u);
  EXPECT_EQ(delta(Drop::Malformed), 3u);
  EXPECT_EQ(delta(Drop::SeqJump), 1u);
  EXPECT_EQ(delta(Drop::BadMac), 4u);  // the one for a held id: relayed without robot 3's tags
  EXPECT_EQ(victim.db().get(3, 5)->data, stored);
  EXPECT_EQ(victim.db().size(), held);
  // After a restart the replay protection still holds.
  run.net().restart(1);
  for (std::size_t k = 0; k < 5 && k < captured.size(); ++k) run.net().inject(0, captured[k]);
  run.net().run(kSecond);
  EXPECT_GE(run.net().node(1).dropped(Drop::Replay), 5u);
  EXPECT_EQ(run.net().node(1).db().size(), held);
  run.expectExactlyOnceInOrder();
}

TEST(PeerSyncSim, ARelayCannotForgeABundleOfAnotherOrigin) {
  // Robot 11 holds its own pair keys only; it relays to robot 7 a bundle "of robot 3" (which
  // robot 3 overhears too).
  Scenario s;
  s.bundles = 5;
  SimRun run(s, "relay_forgery");
  run.produce();
  run.converge(20 * kSecond);
  PeerSyncNode& victim = run.net().node(1);
  const std::uint64_t bad_before = victim.dropped(Drop::BadMac);
  std::mt19937 rng(9);
  const std::int32_t seq = victim.db().held().at(kIds[0]).max() + 1;
  const Bytes forged = encodeBundle(randomBundle(rng, kIds[0], seq));
  const MessageAuth relay = authOf(kIds[2], kTeam);
  // What it can make: no tags, its own tags as if it were the origin, and robot 3's tags made
  // with the keys it holds (right only in the slot of the pair {3, 11}, i.e. for itself).
  const PairKeys held = derivePairKeys("team-secret", kIds[2], kTeam);
  const MessageAuth impostor(kIds[0], kTeam, {{kIds[1], held.at(kIds[0])}, {kIds[2], held.at(kIds[0])}, {20, held.at(20)}});
  std::int64_t counter = SimNetwork::kSimEpoch + run.net().now() + 100 * kSecond;
  auto relayWith = [&](const Bytes& data, const Bytes* tags) {
    Chunk c;
    c.sender = kIds[2];
    c.receiver = kIds[1];
    c.counter = ++counter;
    c.origin = kIds[0];
    c.seq = seq;
    c.data = packBundles({&data}, {tags});
    relay.sign(c);
    run.net().inject(2, c);
  };
  const Bytes own_tags = relay.bundleTags(seq, forged), impostor_tags = impostor.bundleTags(seq, forged);
  relayWith(forged, nullptr);
  relayWith(forged, &own_tags);
  relayWith(forged, &impostor_tags);
  run.net().run(kSecond);
  EXPECT_EQ(victim.dropped(Drop::BadMac) - bad_before, 3u);
  EXPECT_FALSE(victim.db().has(kIds[0], seq));
  // Nor does robot 3 take it as its own bundle given back (and then vouch for it).
  EXPECT_FALSE(run.net().node(0).db().has(kIds[0], seq));
  // The same relay with robot 3's own tags (as a true relay forwards them) is taken.
  const Bytes origin_tags = authOf(kIds[0], kTeam).bundleTags(seq, forged);
  relayWith(forged, &origin_tags);
  run.net().run(kSecond);
  EXPECT_TRUE(victim.db().has(kIds[0], seq));
  EXPECT_EQ(victim.dropped(Drop::BadMac) - bad_before, 3u);
}

TEST(PeerSyncSim, OwnInputGoingBackwardsOrJumpingFarIsRefused) {
  SyncConfig cfg = teamConfig(3, kTeam);
  cfg.max_seq_jump = 1000;
  PeerSyncNode node(cfg, "", 0);
  std::mt19937 rng(3);
  EXPECT_FALSE(node.addOwnBundle(randomBundle(rng, 3, 10), 0));
  EXPECT_FALSE(node.addOwnBundle(randomBundle(rng, 3, 11), 0));
  EXPECT_EQ(node.addOwnBundle(randomBundle(rng, 3, 11), 0), Drop::Duplicate);
  EXPECT_EQ(node.addOwnBundle(randomBundle(rng, 3, 5), 0), Drop::SeqBackwards);
  EXPECT_EQ(node.addOwnBundle(randomBundle(rng, 3, 1013), 0), Drop::SeqJump);  // 1001 missing: over the limit
  EXPECT_EQ(node.addOwnBundle(randomBundle(rng, 7, 12), 0), Drop::WrongOrigin);
  EXPECT_EQ(node.db().size(), 2u);
  EXPECT_FALSE(node.addOwnBundle(randomBundle(rng, 3, 12), 0));
  EXPECT_EQ(node.dropped(Drop::Lost), 0u);
}

TEST(PeerSyncSim, MapsAreSharedAndNewestWins) {
  Scenario s;
  s.bundles = 3;
  SimRun run(s, "maps");
  std::mt19937 rng(9);
  SharedMap m;
  m.frame_robot = kIds[0];
  for (int i = 0; i < 400; ++i) m.objects.push_back(randomObject(rng, i));  // several chunks
  run.net().node(0).setOwnMap(m, run.net().now());
  run.produce();
  auto maps = run.net().node(2).takeMaps();
  ASSERT_EQ(maps.size(), 1u);
  EXPECT_EQ(maps[0].robot, kIds[0]);
  EXPECT_EQ(maps[0].objects.size(), 400u);
  EXPECT_EQ(run.net().node(2).landmarks(kIds[0]), 400u);
  EXPECT_TRUE(run.net().node(2).takeMaps().empty());
}

// A map that keeps changing a little: after the first whole map, peers get the changes against
// the version their heartbeats say they hold, under loss, and end with the latest version.
TEST(PeerSyncSim, MapChangesGoOutAgainstTheVersionPeersHold) {
  Scenario s;
  s.bundles = 2;
  s.loss = 0.2;
  SimRun run(s, "map_changes");
  std::mt19937 rng(11);
  std::size_t whole = 0, changes = 0, whole_bytes = 0, change_bytes = 0;
  run.net().on_send = [&](std::size_t from, const TeamMessage& m) {
    const auto* c = std::get_if<Chunk>(&m);
    if (!c || from != 0) return;
    if (c->kind == ChunkKind::Map) ++whole, whole_bytes += c->data.size();
    if (c->kind == ChunkKind::MapDelta) ++changes, change_bytes += c->data.size();
  };
  SharedMap m;
  m.frame_robot = kIds[0];
  for (int i = 0; i < 200; ++i) m.objects.push_back(randomObject(rng, i));
  std::uniform_int_distribution<int> pick(0, 199);
  for (int round = 0; round < 8; ++round) {
    for (int k = 0; k < 5; ++k) {  // a few landmarks move, one is new
      Object& o = m.objects[static_cast<std::size_t>(pick(rng))];
      o = randomObject(rng, o.id);
    }
    m.objects.push_back(randomObject(rng, 1000 + round));
    run.net().node(0).setOwnMap(m, run.net().now());
    run.net().run(200 * kSecond);  // longer than map_period_s (defaults: 90 s)
  }
  run.net().node(0).setOwnMap(m, run.net().now());  // unchanged content, a new version
  run.converge(10 * kSecond);
  run.net().run(300 * kSecond);  // lost sends are repeated at map_refresh_s
  for (std::size_t i : {std::size_t{1}, std::size_t{2}}) {
    std::vector<SharedMap> maps = run.net().node(i).takeMaps();
    ASSERT_FALSE(maps.empty()) << "robot " << kIds[i];
    const SharedMap& got = maps.back();
    ASSERT_EQ(got.objects.size(), m.objects.size()) << "robot " << kIds[i];
    const std::optional<SharedMap> whole_now = decodeMap(encodeMap(m), kIds[0], got.version, nullptr);
    for (const Object& o : whole_now->objects) {
      const auto it = std::find_if(got.objects.begin(), got.objects.end(), [&](const Object& g) { return g.id == o.id; });
      ASSERT_NE(it, got.objects.end()) << "robot " << kIds[i] << " lacks object " << o.id;
      EXPECT_LE((it->position() - o.position()).norm(), 0.14) << "object " << o.id;
    }
  }
  EXPECT_GE(changes, 5u);
  EXPECT_LT(change_bytes / std::max<std::size_t>(1, changes), whole_bytes / std::max<std::size_t>(1, whole) / 4);
}

TEST(PeerSyncSim, ThinnedPayloadsAreReproducedAfterARestart) {
  const std::string dir = freshDir("thin_restart");
  SyncConfig c = teamConfig(kIds[0], kTeam);
  c.thin_observations = true;
  std::mt19937 rng(17);
  std::vector<Bytes> before;
  std::size_t full_objects = 0, shared_objects = 0;
  {
    PeerSyncNode node(c, dir, 0);
    Pose odom = Pose::Identity();
    for (int k = 0; k < 120; ++k) {
      KeyPoseBundle b = randomBundle(rng, kIds[0], k, 0);
      b.relative_odom = poseFromXyzYaw(1.4, 0, 0, 0.05 * std::sin(k * 0.1));
      odom = odom * b.relative_odom;
      b.odom_pose = odom;
      for (int i = 0; i < 12; ++i) {  // each trunk seen in 12 key poses, with noise
        Object o;
        o.id = (k + i) / 12 * 12 + i;
        o.class_id = 71;
        o.confidence = 0.5 + 0.04 * i;
        o.model = Cylinder{{3.0 + 0.01 * (rng() % 50), 1.0 * i - 6, 0}, Eigen::Vector3d::UnitZ(), 0.2, 5.0 + 0.01 * (rng() % 50)};
        b.objects.push_back(o);
      }
      full_objects += b.objects.size();
      ASSERT_FALSE(node.addOwnBundle(b, 0));
      before.push_back(*node.wirePayload(kIds[0], k));
      std::string err;
      shared_objects += decodeBundle(before.back(), kIds[0], k, &err, nullptr)->objects.size();
    }
  }
  EXPECT_LT(shared_objects, full_objects / 2);
  PeerSyncNode again(c, dir, 0);
  for (int k = 0; k < 120; ++k) ASSERT_EQ(*again.wirePayload(kIds[0], k), before[static_cast<std::size_t>(k)]) << k;
  fs::remove_all(dir);
}
