#include <gtest/gtest.h>

#include <random>

#include "team/observation_thinning.h"
#include "team/sync_config.h"

using namespace slide;
using namespace slide::team;

namespace {

Object trunk(std::int64_t id, double radius = 0.2) {
  Object o;
  o.id = id;
  o.class_id = 71;
  o.model = Cylinder{{5, 1, 0}, Eigen::Vector3d::UnitZ(), radius, 6};
  return o;
}

KeyPoseBundle at(std::int32_t seq, double x, double yaw, std::vector<Object> objects) {
  KeyPoseBundle b;
  b.robot = 1;
  b.seq = seq;
  b.odom_pose = poseFromXyzYaw(x, 0, 0, yaw);
  b.objects = std::move(objects);
  return b;
}

std::vector<std::int64_t> ids(const KeyPoseBundle& b) {
  std::vector<std::int64_t> out;
  for (const auto& o : b.objects) out.push_back(o.id);
  return out;
}

}  // namespace

TEST(ObservationThinning, FirstObservationAlwaysThenOnlyAfterTravel) {
  ObservationThinning t(ThinningPolicy{true, 5.0, 45.0, 0.3, 1});
  EXPECT_EQ(ids(t.thin(at(0, 0, 0, {trunk(1), trunk(2)}))), (std::vector<std::int64_t>{1, 2}));
  EXPECT_TRUE(t.thin(at(1, 1.4, 0, {trunk(1), trunk(2)})).objects.empty());
  // A new track is shared at once, whatever the travel.
  EXPECT_EQ(ids(t.thin(at(2, 2.8, 0, {trunk(1), trunk(3)}))), (std::vector<std::int64_t>{3}));
  const KeyPoseBundle empty = t.thin(at(3, 4.2, 0.1, {trunk(1)}));
  EXPECT_TRUE(empty.objects.empty());
  EXPECT_EQ(empty.seq, 3);  // the key pose itself is kept, odometry and all
  EXPECT_TRUE(empty.odom_pose.isApprox(poseFromXyzYaw(4.2, 0, 0, 0.1)));
  // 5 m since track 1 was last shared; track 3 only 2.2 m.
  EXPECT_EQ(ids(t.thin(at(4, 5.0, 0, {trunk(1), trunk(3)}))), (std::vector<std::int64_t>{1}));
}

TEST(ObservationThinning, TurnClassAndSizeChangesAreShared) {
  ObservationThinning t(ThinningPolicy{true, 5.0, 45.0, 0.3, 1});
  t.thin(at(0, 0, 0, {trunk(1), trunk(2), trunk(3)}));
  Object reclassified = trunk(2);
  reclassified.class_id = 80;
  Object grown = trunk(3, 0.4);  // diameter +0.4 m
  EXPECT_EQ(ids(t.thin(at(1, 0.5, 0.2, {trunk(1), reclassified, grown}))), (std::vector<std::int64_t>{2, 3}));
  EXPECT_TRUE(t.thin(at(2, 0.5, 0.7, {trunk(1)})).objects.empty());  // turned 40 deg
  EXPECT_EQ(ids(t.thin(at(3, 0.5, 0.8, {trunk(1)}))), (std::vector<std::int64_t>{1}));  // 45.8 deg
}

// A peer's optimizer confirms a landmark from min_observations (3) observations: a track's
// first three go out whatever the travel, then only after travel (5 m here).
TEST(ObservationThinning, ATracksFirstSharesAllGoOut) {
  ObservationThinning t(ThinningPolicy{true, 5.0, 45.0, 0.3, 3});
  ASSERT_EQ(ThinningPolicy{}.min_shares, 3);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(ids(t.thin(at(k, 0.5 * k, 0, {trunk(1)}))), (std::vector<std::int64_t>{1})) << k;
  EXPECT_TRUE(t.thin(at(3, 1.5, 0, {trunk(1)})).objects.empty());
  EXPECT_TRUE(t.thin(at(4, 5.9, 0, {trunk(1)})).objects.empty());  // 4.9 m since the third
  EXPECT_EQ(ids(t.thin(at(5, 6.0, 0, {trunk(1)}))), (std::vector<std::int64_t>{1}));
}

TEST(ObservationThinning, DeterministicAndOffMeansEverything) {
  std::mt19937 rng(3);
  std::vector<KeyPoseBundle> stream;
  for (int k = 0; k < 200; ++k) {
    std::vector<Object> objects;
    for (int i = 0; i < 10; ++i) objects.push_back(trunk((k + static_cast<int>(rng() % 20)) / 3));
    stream.push_back(at(k, 1.4 * k, 0.05 * k, objects));
  }
  ObservationThinning a(ThinningPolicy{}), b(ThinningPolicy{}), off(ThinningPolicy{false, 5, 45, 0.3});
  std::size_t shared = 0, all = 0;
  for (const KeyPoseBundle& x : stream) {
    const KeyPoseBundle ta = a.thin(x);
    EXPECT_EQ(ids(ta), ids(b.thin(x)));
    EXPECT_EQ(ids(off.thin(x)), ids(x));
    shared += ta.objects.size();
    all += x.objects.size();
  }
  EXPECT_LT(shared, all / 2);
}

TEST(ObservationThinning, ConfigKeysAreValidated) {
  auto load = [](const std::string& extra) {
    return SyncConfig::fromConfig(ConfigNode::parse("team: [1]\n" + extra, "t.yaml"), 1);
  };
  const SyncConfig c =
      load("thin_observations: false\nthin_travel_m: 8\nthin_turn_deg: 30\nthin_size_change_m: 0.5\nthin_min_shares: 2\n");
  EXPECT_FALSE(c.thinning().enabled);
  EXPECT_EQ(c.thinning().travel_m, 8.0);
  EXPECT_EQ(c.thinning().turn_deg, 30.0);
  EXPECT_EQ(c.thinning().size_change_m, 0.5);
  EXPECT_EQ(c.thinning().min_shares, 2);
  for (const std::string bad : {"thin_travel_m: -1\n", "thin_turn_deg: -5\n", "thin_size_change_m: -0.1\n",
                                "thin_observations: maybe\n", "thin_min_shares: 0\n"}) {
    try {
      load(bad);
      FAIL() << "accepted " << bad;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(bad.substr(0, bad.find(':'))), std::string::npos) << e.what();
    }
  }
}
