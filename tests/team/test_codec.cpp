#include <gtest/gtest.h>

#include "team/codec.h"
#include "team_test_util.h"

using namespace slide;
using namespace slide::team;
using namespace slide::team::testing;

namespace {
void expectNear(const Object& a, const Object& b) {
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.class_id, b.class_id);
  EXPECT_EQ(a.shape(), b.shape());
  EXPECT_EQ(a.num_observations, b.num_observations);
  EXPECT_NEAR(a.confidence, b.confidence, 1e-6);
  EXPECT_LT((a.position() - b.position()).norm(), 1e-5);
  EXPECT_LT((a.extent() - b.extent()).norm(), 1e-5);
  if (a.shape() == Shape::Cuboid) {
    EXPECT_TRUE(std::get<Cuboid>(a.model).pose.isApprox(std::get<Cuboid>(b.model).pose, 1e-5));
  }
  if (a.shape() == Shape::Cylinder) {
    EXPECT_LT((std::get<Cylinder>(a.model).axis - std::get<Cylinder>(b.model).axis).norm(), 1e-6);
  }
}
}  // namespace

TEST(Codec, BundleRoundTripIsFloat32CloseAndStable) {
  std::mt19937 rng(7);
  for (int k = 0; k < 200; ++k) {
    Bundle b = randomBundle(rng, 2, k, k % 25);
    b.first = k % 3 == 0;
    const Bytes enc = encodeBundle(b);
    std::string err;
    const auto d = decodeBundle(enc, 2, k, &err);
    ASSERT_TRUE(d) << err;
    EXPECT_EQ(d->first, b.first);
    EXPECT_EQ(d->utime, b.utime);
    EXPECT_TRUE(d->odom_pose.isApprox(b.odom_pose, 1e-5));
    EXPECT_TRUE(d->relative_odom.isApprox(b.relative_odom, 1e-5));
    EXPECT_EQ(d->odom_sigma, b.odom_sigma);
    ASSERT_EQ(d->objects.size(), b.objects.size());
    for (std::size_t i = 0; i < b.objects.size(); ++i) expectNear(d->objects[i], b.objects[i]);
    // Re-encoding what was received changes nothing beyond float rounding (relays forward the
    // original bytes anyway).
    EXPECT_TRUE(bundlesNear(*decodeBundle(encodeBundle(*d), 2, k, &err), b));
    EXPECT_EQ(encodeBundle(*d).size(), enc.size());
  }
}

TEST(Codec, CompactSizes) {
  // An upright trunk with default confidence costs 1 tag + 1 id + 1 class + 12 root + 8 = 23.
  Bundle b;
  Object o;
  o.id = 5;
  o.class_id = 71;
  o.model = Cylinder{{3, 4, -0.5}, Eigen::Vector3d::UnitZ(), 0.2, 6};
  b.objects.push_back(o);
  const std::size_t base = encodeBundle(Bundle{}).size();
  EXPECT_EQ(encodeBundle(b).size() - base, 23u);
  EXPECT_EQ(base, 2u + 1u + 2 * 21u + 1u);  // format, flags, utime 0, two yaw-only poses, count
}

TEST(Codec, EveryTruncationAndCorruptionIsRejectedWithoutCrash) {
  std::mt19937 rng(11);
  const Bundle b = randomBundle(rng, 1, 3, 12);
  const Bytes enc = encodeBundle(b);
  std::string err;
  for (std::size_t n = 0; n < enc.size(); ++n) {
    const Bytes cut(enc.begin(), enc.begin() + static_cast<std::ptrdiff_t>(n));
    EXPECT_FALSE(decodeBundle(cut, 1, 3, &err)) << n;
    EXPECT_FALSE(err.empty());
  }
  Bytes longer = enc;
  longer.push_back(0);
  EXPECT_FALSE(decodeBundle(longer, 1, 3, &err));
  EXPECT_NE(err.find("trailing"), std::string::npos);
  for (int k = 0; k < 2000; ++k) {  // random corruption: decodes or fails, never crashes
    Bytes bad = enc;
    bad[rng() % bad.size()] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    (void)decodeBundle(bad, 1, 3, &err);
  }
}

TEST(Codec, MapRoundTrip) {
  std::mt19937 rng(5);
  SharedMap m;
  m.robot = 2;
  m.frame_robot = 2;
  m.version = 9;
  m.utime = 123456;
  for (int i = 0; i < 300; ++i) m.objects.push_back(randomObject(rng, i));
  const Bytes enc = encodeMap(m);
  std::string err;
  const auto d = decodeMap(enc, 2, 9, &err);
  ASSERT_TRUE(d) << err;
  EXPECT_EQ(d->utime, m.utime);
  EXPECT_EQ(d->frame_robot, 2);
  ASSERT_EQ(d->objects.size(), m.objects.size());
  for (std::size_t i = 0; i < m.objects.size(); ++i) {
    const Object &a = d->objects[i], &b = m.objects[i];
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(a.class_id, b.class_id);
    EXPECT_EQ(a.shape(), b.shape());
    if (a.shape() == Shape::Cylinder) {  // upright in the map: root and size kept
      EXPECT_LT((std::get<Cylinder>(a.model).root - std::get<Cylinder>(b.model).root).norm(), 1e-5);
      EXPECT_NEAR(std::get<Cylinder>(a.model).radius, std::get<Cylinder>(b.model).radius, 1e-6);
    } else {
      EXPECT_LT((a.position() - b.position()).norm(), 1e-5);
      EXPECT_LT((a.extent() - b.extent()).norm(), 1e-5);
    }
    if (a.shape() == Shape::Cuboid) {
      EXPECT_NEAR(yawOf(std::get<Cuboid>(a.model).pose.linear()), yawOf(std::get<Cuboid>(b.model).pose.linear()), 1e-5);
    }
  }
  EXPECT_FALSE(decodeMap(Bytes(enc.begin(), enc.end() - 1), 2, 9, &err));
}

TEST(Codec, RelativeOdometryDerivableFromPosesIsLeftOut) {
  std::mt19937 rng(21);
  std::string err;
  Bundle prev = randomBundle(rng, 1, 4, 3);
  Bundle b = randomBundle(rng, 1, 5, 3);
  b.odom_pose = prev.odom_pose * b.relative_odom;  // what a tracker publishes
  const Bytes explicit_rel = encodeBundle(b);
  const Pose prev_rx = decodeBundle(encodeBundle(prev), 1, 4, &err)->odom_pose;  // as receivers hold it
  const Bytes derived = encodeBundle(b, &prev_rx);
  EXPECT_EQ(explicit_rel.size() - derived.size(), 25u);  // one pose (tag, 3 + 3 floats) fewer
  bool needs = false;
  const auto alone = decodeBundle(derived, 1, 5, &err, nullptr, &needs);
  ASSERT_TRUE(alone) << err;
  EXPECT_TRUE(needs);
  // The receiver has the float32 poses of both bundles: the relative motion comes back close.
  const auto full = decodeBundle(derived, 1, 5, &err, &prev_rx, &needs);
  ASSERT_TRUE(full) << err;
  EXPECT_FALSE(needs);
  EXPECT_LT((full->relative_odom.translation() - b.relative_odom.translation()).norm(), 1e-4);
  EXPECT_LT((full->relative_odom.linear() - b.relative_odom.linear()).norm(), 1e-5);
  // Not derivable (or a first bundle): written out.
  Bundle other = b;
  other.relative_odom = poseFromXyzYaw(1, 2, 0, 0.3);
  EXPECT_EQ(encodeBundle(other, &prev_rx).size(), encodeBundle(other).size());
  other = b;
  other.first = true;
  EXPECT_EQ(encodeBundle(other, &prev_rx).size(), explicit_rel.size());
}
