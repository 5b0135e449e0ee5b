#include <gtest/gtest.h>

#include "team/bundle_pack.h"
#include "team/codec.h"
#include "team/quantise.h"
#include "team_test_util.h"

using namespace slide;
using namespace slide::team;
using namespace slide::team::testing;

namespace {

double rotationError(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

// Within the quantisation stated in codec.h.
void expectQuantisedCopy(const Object& got, const Object& want) {
  EXPECT_EQ(got.id, want.id);
  EXPECT_EQ(got.class_id, want.class_id);
  EXPECT_EQ(got.shape(), want.shape());
  EXPECT_EQ(got.num_observations, want.num_observations);
  EXPECT_LE(std::abs(got.confidence - want.confidence), 0.5 / 255 + 1e-9);
  if (const auto* c = std::get_if<Cylinder>(&want.model)) {
    const auto& g = std::get<Cylinder>(got.model);
    EXPECT_LE((g.root - c->root).cwiseAbs().maxCoeff(), 0.005 + 1e-9);
    EXPECT_LE(std::acos(std::min(1.0, g.axis.dot(c->axis.normalized()))), 1e-3);
    EXPECT_LE(std::abs(g.radius - c->radius), 0.005 + 1e-9);
    EXPECT_LE(std::abs(g.length - c->length), 0.05 + 1e-9);
  } else if (const auto* b = std::get_if<Cuboid>(&want.model)) {
    const auto& g = std::get<Cuboid>(got.model);
    EXPECT_LE((g.pose.translation() - b->pose.translation()).cwiseAbs().maxCoeff(), 0.005 + 1e-9);
    EXPECT_LE(rotationError(g.pose.linear(), b->pose.linear()), 1e-3);
    EXPECT_LE(std::abs(wrapAngle(yawOf(g.pose.linear()) - yawOf(b->pose.linear()))), 1e-4);
    EXPECT_LE((g.dims - b->dims).cwiseAbs().maxCoeff(), 0.025 + 1e-9);
  } else {
    const auto& e = std::get<Ellipsoid>(want.model);
    const auto& g = std::get<Ellipsoid>(got.model);
    EXPECT_LE((g.centroid - e.centroid).cwiseAbs().maxCoeff(), 0.005 + 1e-9);
    EXPECT_LE(std::abs(g.radius - e.radius), 0.005 + 1e-9);
    EXPECT_LE(std::abs(g.height - e.height), 0.025 + 1e-9);
  }
}

void expectSigmaNear(const Vector6d& got, const Vector6d& want) {
  for (int i = 0; i < 6; ++i) EXPECT_LE(std::abs(got[i] - want[i]), 0.022 * want[i] + 1e-9) << i;
}

// A tracker-like stream: odometry poses composed from the relative motion.
std::vector<KeyPoseBundle> trackerStream(std::mt19937& rng, int n) {
  std::vector<KeyPoseBundle> out;
  Pose odom = poseFromXyzYaw(120.5, -80.25, 0.3, 2.0);
  for (int k = 0; k < n; ++k) {
    KeyPoseBundle b = randomBundle(rng, 4, k, 3);
    b.first = k == 0;
    // Growing slowly (as a tracker's per-metre model): mostly the same after quantisation.
    b.odom_sigma << 0.02f + 1e-5f * k, 0.02f, 0.01f, 0.002f, 0.002f, 0.005f;
    if (k > 0) odom = odom * b.relative_odom;
    b.odom_pose = odom;
    out.push_back(b);
  }
  return out;
}

}  // namespace

TEST(Codec, BundleRoundTripIsWithinTheStatedQuantisationAndStable) {
  std::mt19937 rng(7);
  for (int k = 0; k < 300; ++k) {
    KeyPoseBundle b = randomBundle(rng, 2, k, k % 25);
    b.first = k % 3 == 0;
    const Bytes enc = encodeBundle(b);
    std::string err;
    const auto d = decodeBundle(enc, 2, k, &err);
    ASSERT_TRUE(d) << err;
    EXPECT_EQ(d->first, b.first);
    EXPECT_EQ(d->utime, b.utime);
    expectSigmaNear(d->odom_sigma, b.odom_sigma);
    EXPECT_TRUE(d->odom_pose.isApprox(b.odom_pose, 1e-5));  // float32 when not chained
    EXPECT_LE((d->relative_odom.translation() - b.relative_odom.translation()).cwiseAbs().maxCoeff(), 0.5e-3 + 1e-9);
    EXPECT_LE(rotationError(d->relative_odom.linear(), b.relative_odom.linear()), 0.9e-4);
    ASSERT_EQ(d->objects.size(), b.objects.size());
    for (std::size_t i = 0; i < b.objects.size(); ++i) expectQuantisedCopy(d->objects[i], b.objects[i]);
    // Quantising again changes nothing: relays and restarts reproduce the same bytes.
    EXPECT_EQ(encodeBundle(*d), enc);
  }
}

TEST(Codec, CompactSizes) {
  // A slightly tilted trunk: tag, id, class, confidence, count, 3 positions (2+2+1), 2 tilt,
  // radius, length = 14 bytes; the next trunk of the same class drops the class byte.
  KeyPoseBundle b;
  Object o;
  o.id = 5;
  o.class_id = 71;
  o.confidence = 0.8;
  o.num_observations = 12;
  o.model = Cylinder{{3, 4, -0.5}, Eigen::Vector3d(0.01, -0.02, 1).normalized(), 0.2, 6};
  b.objects.push_back(o);
  const std::size_t base = encodeBundle(KeyPoseBundle{}).size();
  EXPECT_EQ(encodeBundle(b).size() - base, 14u);
  o.id = 6;
  b.objects.push_back(o);
  EXPECT_EQ(encodeBundle(b).size() - base, 14u + 13u);
  // format, flags, utime 0, yaw-only float32 pose (1 + 2*4 + 3*4), identity step (6), count
  EXPECT_EQ(base, 2u + 1u + 21u + 6u + 1u);
}

TEST(Codec, ChainedOdometryHasNoDriftAndNeedsThePreviousBundle) {
  std::mt19937 rng(21);
  const auto stream = trackerStream(rng, 1000);
  std::optional<BundleContext> previous;
  std::size_t chained_bytes = 0, alone_bytes = 0;
  for (const KeyPoseBundle& b : stream) {
    const Bytes enc = encodeBundle(b, previous ? &*previous : nullptr);
    EXPECT_EQ(chainedBundle(enc), !b.first);
    std::string err;
    const auto d = decodeBundle(enc, 4, b.seq, &err, previous ? &*previous : nullptr);
    ASSERT_TRUE(d) << err;
    EXPECT_EQ(d->utime, b.utime);
    expectSigmaNear(d->odom_sigma, b.odom_sigma);
    // Each step is quantised against the decoded previous pose: the error never accumulates.
    EXPECT_LE((d->odom_pose.translation() - b.odom_pose.translation()).norm(), 0.9e-3) << b.seq;
    EXPECT_LE(rotationError(d->odom_pose.linear(), b.odom_pose.linear()), 1e-4) << b.seq;
    if (!b.first) {
      EXPECT_LE((d->relative_odom.translation() - b.relative_odom.translation()).norm(), 2e-3);
      EXPECT_LE(rotationError(d->relative_odom.linear(), b.relative_odom.linear()), 2e-4);
      chained_bytes += enc.size();
      alone_bytes += encodeBundle(b).size();
      bool needs = false;
      const auto alone = decodeBundle(enc, 4, b.seq, &err, nullptr, &needs);
      ASSERT_TRUE(alone) << err;
      EXPECT_TRUE(needs);
    }
    previous = BundleContext::of(*d, chainedBundle(enc) ? &*previous : nullptr);
  }
  EXPECT_LT(chained_bytes + 25 * (stream.size() - 1), alone_bytes);  // >= 25 bytes saved each
  // Not consistent with the poses (or a first bundle): self-contained.
  KeyPoseBundle other = stream[5];
  other.relative_odom = poseFromXyzYaw(1, 2, 0, 0.3);
  EXPECT_FALSE(chainedBundle(encodeBundle(other, &*previous)));
  other = stream[5];
  other.first = true;
  EXPECT_FALSE(chainedBundle(encodeBundle(other, &*previous)));
}

// Team bundles leave out the tracks' observation counts (one varint byte each here) and keep
// the detector confidence, which a peer's optimizer weighs class votes by.
TEST(Codec, TeamBundlesLeaveOutTrackCountsAndKeepConfidence) {
  std::mt19937 rng(5);
  KeyPoseBundle b = randomBundle(rng, 3, 7);
  ASSERT_FALSE(b.objects.empty());
  for (std::size_t i = 0; i < b.objects.size(); ++i) b.objects[i].confidence = i % 2 ? 0.05 : 0.7, b.objects[i].num_observations = 12;
  const Bytes full = encodeBundle(b), team = encodeBundle(b, nullptr, BundleDetail::Team);
  EXPECT_EQ(full.size() - team.size(), b.objects.size());  // one byte each, per object
  std::string err;
  const auto d = decodeBundle(team, 3, 7, &err);
  ASSERT_TRUE(d) << err;
  ASSERT_EQ(d->objects.size(), b.objects.size());
  for (std::size_t i = 0; i < b.objects.size(); ++i) {
    EXPECT_NEAR(d->objects[i].confidence, b.objects[i].confidence, 0.5 / 255);
    EXPECT_EQ(d->objects[i].num_observations, 1);
    Object expect = b.objects[i];
    expect.num_observations = 1;
    expectQuantisedCopy(d->objects[i], expect);
  }
  EXPECT_EQ(encodeBundle(*d, nullptr, BundleDetail::Team), team);  // stable
}

// A box whose length went unseen travels with its other reading (the box turned a quarter
// about its vertical, grown from the same face): the receiving optimizer keeps the reading its
// landmark agrees with, as it does with its own robot's. It costs the other centre's offset (5 cm
// units) and extents, 6 bytes here; on a tilted body too.
TEST(Codec, ABoxTravelsWithItsOtherReading) {
  for (const double roll : {0.0, 0.05}) {
    KeyPoseBundle b;
    Object car;
    car.id = 4;
    car.class_id = 10;
    car.confidence = 0.9;
    const Pose body_tilt = poseFromXyzRpy(Eigen::Vector3d::Zero(), roll, -0.02, 0);
    const Pose primary = body_tilt * poseFromXyzYaw(12.3, -4.1, 0.7, 0.4);
    car.model = Cuboid{primary, {4.5, 1.8, 1.5}};
    Pose turned = body_tilt * poseFromXyzYaw(12.3 + 1.35 * std::cos(0.4), -4.1 + 1.35 * std::sin(0.4), 0.7, 0.4 + M_PI / 2);
    car.other_reading = Cuboid{turned, {4.5, 1.75, 1.5}};
    Object single = car;
    single.other_reading.reset();
    b.objects = {car};
    const Bytes with = encodeBundle(b, nullptr, BundleDetail::Team);
    b.objects = {single};
    const Bytes without = encodeBundle(b, nullptr, BundleDetail::Team);
    EXPECT_EQ(with.size() - without.size(), 6u);
    std::string err;
    const auto d = decodeBundle(with, 0, 0, &err);
    ASSERT_TRUE(d) << err;
    ASSERT_EQ(d->objects.size(), 1u);
    expectQuantisedCopy(d->objects[0], car);
    ASSERT_TRUE(d->objects[0].other_reading.has_value());
    Object other = car, got = d->objects[0];
    other.model = *car.other_reading;
    got.model = *got.other_reading;
    got.other_reading.reset();
    other.other_reading.reset();
    const auto& gb = std::get<Cuboid>(got.model);
    const auto& ob = std::get<Cuboid>(other.model);
    EXPECT_LE((gb.pose.translation() - ob.pose.translation()).cwiseAbs().maxCoeff(), 0.025 + 1e-9);
    EXPECT_LE(rotationError(gb.pose.linear(), ob.pose.linear()), 1e-3);
    EXPECT_LE((gb.dims - ob.dims).cwiseAbs().maxCoeff(), 0.025 + 1e-9);
    EXPECT_EQ(encodeBundle(*d, nullptr, BundleDetail::Team), with);  // stable
    // The robot's own journal keeps it too.
    b.objects = {car};
    const auto own = decodeBundle(encodeBundle(b), 0, 0, &err);
    ASSERT_TRUE(own) << err;
    EXPECT_TRUE(own->objects[0].other_reading.has_value());
  }
}

TEST(Codec, AxesPointingDownOrSidewaysComeBack) {
  KeyPoseBundle b;
  for (const Eigen::Vector3d& axis : {Eigen::Vector3d(0.1, 0.2, -0.97), Eigen::Vector3d(1, 0, 0),
                                      Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(-0.6, 0.8, 0),
                                      Eigen::Vector3d(0.70755, 0.70666, 0)}) {  // rounds beyond unit norm
    Object o;
    o.id = static_cast<std::int64_t>(b.objects.size());
    o.model = Cylinder{{1, 2, 3}, axis.normalized(), 0.3, 4};
    b.objects.push_back(o);
  }
  std::string err;
  const auto d = decodeBundle(encodeBundle(b), 0, 0, &err);
  ASSERT_TRUE(d) << err;
  for (std::size_t i = 0; i < b.objects.size(); ++i) expectQuantisedCopy(d->objects[i], b.objects[i]);
}

TEST(Codec, OutOfRangeValuesAreEscapedNotClamped) {
  KeyPoseBundle b;
  Object far;  // 400 m away in the body frame, size beyond 2.55 m radius, confidence > 1
  far.id = 1;
  far.class_id = 71;
  far.confidence = 1.5;
  far.model = Cylinder{{400.123, -3, 0}, Eigen::Vector3d::UnitZ(), 3.2, 40.0};
  Object neg;  // negative size
  neg.id = 2;
  neg.model = Ellipsoid{{1, 2, 3}, -0.5, 1.0};
  Object huge;  // cuboid 20 m long
  huge.id = 3;
  huge.model = Cuboid{poseFromXyzYaw(1, 1, 0, 0.5), {20.0, 2.5, 3.0}};
  b.objects = {far, neg, huge};
  std::string err;
  const auto d = decodeBundle(encodeBundle(b), 0, 0, &err);
  ASSERT_TRUE(d) << err;
  const auto& c = std::get<Cylinder>(d->objects[0].model);
  EXPECT_NEAR(c.root.x(), 400.123, 1e-4);  // float32, not the 327 m limit
  EXPECT_NEAR(c.radius, 3.2, 1e-6);
  EXPECT_NEAR(c.length, 40.0, 1e-6);
  EXPECT_NEAR(d->objects[0].confidence, 1.5, 1e-6);
  EXPECT_NEAR(std::get<Ellipsoid>(d->objects[1].model).radius, -0.5, 1e-6);
  EXPECT_NEAR(std::get<Cuboid>(d->objects[2].model).dims.x(), 20.0, 1e-6);
  // Relative odometry beyond 1000 km and a sigma beyond the log scale go as float32.
  KeyPoseBundle jump;
  jump.odom_sigma << 20.0f, 0, 0, 0, 0, 1e-6f;
  jump.relative_odom = poseFromXyzYaw(2e6, 0, 0, 0.1);
  const auto dj = decodeBundle(encodeBundle(jump), 0, 0, &err);
  ASSERT_TRUE(dj) << err;
  EXPECT_NEAR(dj->relative_odom.translation().x(), 2e6, 1.0);
  EXPECT_EQ(dj->odom_sigma, jump.odom_sigma);
}

TEST(Codec, EveryTruncationAndCorruptionIsRejectedWithoutCrash) {
  std::mt19937 rng(11);
  const KeyPoseBundle b = randomBundle(rng, 1, 3, 12);
  const Bytes enc = encodeBundle(b);
  std::string err;
  for (std::size_t n = 0; n < enc.size(); ++n) {
    const Bytes cut(enc.begin(), enc.begin() + static_cast<std::ptrdiff_t>(n));
    err.clear();
    EXPECT_FALSE(decodeBundle(cut, 1, 3, &err)) << n;
    EXPECT_FALSE(err.empty());
  }
  Bytes longer = enc;
  longer.push_back(0);
  EXPECT_FALSE(decodeBundle(longer, 1, 3, &err));
  EXPECT_NE(err.find("trailing"), std::string::npos);
  for (int k = 0; k < 5000; ++k) {  // random corruption: decodes or fails, never crashes
    Bytes bad = enc;
    bad[rng() % bad.size()] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    (void)decodeBundle(bad, 1, 3, &err);
  }
}

TEST(Codec, MalformedFieldsAreNamed) {
  auto rejects = [](const Bytes& data, const std::string& what) {
    std::string err;
    EXPECT_FALSE(decodeBundle(data, 1, 1, &err)) << what;
    EXPECT_NE(err.find(what), std::string::npos) << "'" << err << "' lacks '" << what << "'";
  };
  // Header: format, flags, then a self-contained pose and step.
  ByteWriter head;
  head.u8(3);
  head.u8(0);
  head.svarint(0);
  head.u8(4);  // yaw-only rotation
  for (float v : {1.0f, 0.0f, 0.0f, 0.0f, 0.0f}) head.f32(v);
  auto withStep = [&](std::array<std::int64_t, 6> step) {
    ByteWriter w = head;
    for (auto v : step) w.svarint(v);
    return w;
  };
  Bytes b = withStep({0, 0, 0, 0, 0, 0}).take();
  b.push_back(0);  // no objects
  std::string err;
  ASSERT_TRUE(decodeBundle(b, 1, 1, &err)) << err;

  Bytes x = b;
  x[0] = 1;
  rejects(x, "unknown bundle format");
  x = b;
  x[1] = 0x80;
  rejects(x, "unknown bundle flags");
  x = b;
  x[1] = 0x40 | 1;
  rejects(x, "after a gap is neither first nor chained");
  x = b;
  x[1] = 0x40;
  x.insert(x.begin() + 2, 0);  // gap 0
  rejects(x, "gap length out of range");
  x[2] = 4;  // gap 2 (zigzag varint)
  std::optional<KeyPoseBundle> after_gap = decodeBundle(x, 1, 1, &err);
  ASSERT_TRUE(after_gap) << err;
  EXPECT_EQ(after_gap->gap, 2);
  x = b;
  x[1] = 1 | 4;
  rejects(x, "first bundle cannot refer");
  Bytes rot = withStep({0, 0, 0, 40000, 0, 0}).take();
  rot.push_back(0);
  rejects(rot, "rotation out of range");
  rot = withStep({0, 0, 0, 30000, 30000, 0}).take();
  rot.push_back(0);
  rejects(rot, "rotation exceeds pi");
  x = b;
  x[1] = 16;
  rejects(x, "float32 sigma flag without a sigma");

  auto withObject = [&](const std::vector<std::uint8_t>& tail) {
    ByteWriter w = withStep({0, 0, 0, 0, 0, 0});
    w.varint(1);
    for (auto v : tail) w.u8(v);
    return w.take();
  };
  // tag, id 0, class, confidence, count, position x y z, sizes
  rejects(withObject({3, 0, 71, 255, 2, 0, 0, 0, 10, 10, 0, 0}), "shape 3 unknown");
  rejects(withObject({1 | 4, 0, 255, 2, 0, 0, 0, 10, 10, 0, 0}), "same-class flag on the first object");
  rejects(withObject({1, 0, 0xff, 0xff, 0x7f, 255, 2, 0, 0, 0, 10, 10}), "class id out of int16 range");
  rejects(withObject({2 | 8, 0, 1, 255, 2, 0, 0, 0, 10, 10, 0}), "orientation flag on an ellipsoid");
  rejects(withObject({1 | 128, 0, 71, 255, 2, 0, 0, 0, 10, 10, 0}), "axis-down flag");
  rejects(withObject({2 | 128, 0, 1, 255, 2, 0, 0, 0, 10, 10, 0}), "axis-down flag on an ellipsoid");
  // A box's other reading 2000 m off (40000 units of 5 cm).
  rejects(withObject({0 | 128, 0, 10, 255, 2, 0, 0, 0, 0, 0, 90, 36, 30, 90, 36, 30, 0x80, 0xf1, 0x04, 0, 0}),
          "other reading's position out of range");
  // A tilted axis with components (0.9, 0.9): beyond unit norm (and rounding).
  rejects(withObject({1 | 8, 0, 71, 255, 2, 0, 0, 0, 0x8c, 0x0e, 0x8c, 0x0e, 10, 10}), "axis components exceed");
  // Position 40000 cm in a body frame: beyond the int16 range that the encoder escapes.
  rejects(withObject({1, 0, 71, 255, 2, 0x80, 0xf1, 0x04, 0, 0, 10, 10}), "position out of range");
  // A float32 confidence that is not finite.
  rejects(withObject({1 | 64, 0, 71, 0, 0, 0xc0, 0x7f, 2, 0, 0, 0, 10, 10}), "confidence is not finite");
  rejects(withObject({1, 0, 71, 255}), "object count 1 exceeds");
  rejects(withObject({1 | 64, 0, 71, 0, 0, 0}), "truncated");
}

TEST(Codec, MapRoundTripWithinQuantisation) {
  std::mt19937 rng(5);
  SharedMap m;
  m.robot = 2;
  m.frame_robot = 2;
  m.version = 9;
  m.utime = 123456;
  for (int i = 0; i < 300; ++i) {
    Object o = randomObject(rng, i);
    if (auto* c = std::get_if<Cylinder>(&o.model)) c->root += Eigen::Vector3d(250.0 * i, -1000, 0);  // far away
    m.objects.push_back(o);
  }
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
    EXPECT_EQ(a.confidence, 1.0);
    EXPECT_EQ(a.num_observations, 1);
    if (a.shape() == Shape::Cylinder) {  // upright in the map: root and size kept
      EXPECT_LE((std::get<Cylinder>(a.model).root - std::get<Cylinder>(b.model).root).cwiseAbs().maxCoeff(), 0.025 + 1e-9);
      EXPECT_NEAR(std::get<Cylinder>(a.model).radius, std::get<Cylinder>(b.model).radius, 0.005 + 1e-9);
      EXPECT_EQ(std::get<Cylinder>(a.model).axis, Eigen::Vector3d::UnitZ());
    } else if (a.shape() == Shape::Cuboid) {
      const auto &ga = std::get<Cuboid>(a.model), &gb = std::get<Cuboid>(b.model);
      EXPECT_LE((ga.pose.translation() - gb.pose.translation()).cwiseAbs().maxCoeff(), 0.025 + 1e-9);  // 5 cm
      EXPECT_NEAR(wrapAngle(yawOf(ga.pose.linear()) - yawOf(gb.pose.linear())), 0.0, M_PI / 256 + 1e-9);
      EXPECT_LE((ga.dims - gb.dims).cwiseAbs().maxCoeff(), 0.025 + 1e-9);
    } else {
      EXPECT_LE((a.position() - b.position()).cwiseAbs().maxCoeff(), 0.025 + 1e-9);
    }
  }
  EXPECT_EQ(encodeMap(*d), enc);
  EXPECT_FALSE(decodeMap(Bytes(enc.begin(), enc.end() - 1), 2, 9, &err));
  Bytes bad = enc;
  bad[0] = 1;
  EXPECT_FALSE(decodeMap(bad, 2, 9, &err));
  EXPECT_NE(err.find("unknown map format"), std::string::npos);
  for (int k = 0; k < 3000; ++k) {  // random corruption: decodes or fails, never crashes
    bad = enc;
    for (int j = 0; j < 3; ++j) bad[rng() % bad.size()] = static_cast<std::uint8_t>(rng());
    (void)decodeMap(bad, 2, 9, &err);
  }
}

TEST(Quantise, HalfAUnitAndNoSilentClamping) {
  EXPECT_EQ(quantise(0.0149, 0.01, 100), 1);
  EXPECT_EQ(quantise(-0.015, 0.01, 100), -2);
  EXPECT_FALSE(quantise(1.01, 0.01, 100));
  EXPECT_FALSE(quantise(std::nan(""), 0.01, 100));
  EXPECT_EQ(quantiseU8(2.55, 0.01), 255);
  EXPECT_FALSE(quantiseU8(2.56, 0.01));
  EXPECT_FALSE(quantiseU8(-0.01, 0.01));
  EXPECT_EQ(quantiseSigma(0.0), 0);
  EXPECT_FALSE(quantiseSigma(-0.1));
  EXPECT_FALSE(quantiseSigma(20.0));
  EXPECT_FALSE(quantiseSigma(1e-5));
  for (double s = 2e-4; s < 10; s *= 1.01) EXPECT_LE(std::abs(sigmaOf(*quantiseSigma(s)) - s), 0.022 * s);
  for (double a = -7; a < 7; a += 0.01)
    EXPECT_LE(std::abs(wrapAngle(turn16ToAngle(quantiseTurn16(a)) - a)), M_PI / 65536 + 1e-12);
}

TEST(BundlePack, RoundTripAndMalformedPacksAreNamed) {
  const Bytes a = {3, 2, 3}, b(200, 3), c = {3};  // each starts with its format byte
  const Bytes plain = packBundles({&a, &b, &c});
  EXPECT_EQ(plain.size(), 2 + packedSize(a.size()) + packedSize(b.size()) + packedSize(c.size()));
  EXPECT_EQ(plain.size(), 2 + 3 + 201 + 1u);  // the format byte once: 2 + (1 + 2) + (2 + 199) + (1 + 0)
  const Bytes tags(18, 0xAA);  // its origin's tag block travels with a bundle
  const Bytes pack = packBundles({&a, &b, &c}, {nullptr, &tags, nullptr});
  EXPECT_EQ(pack.size(), 2 + packedSize(a.size(), 0, true) + packedSize(b.size(), tags.size(), true) +
                             packedSize(c.size(), 0, true));
  // With tags, each bundle has a tag length: 2 + (1 + 2 + 1) + (2 + 199 + 1 + 18) + (1 + 0 + 1).
  EXPECT_EQ(pack.size(), 2 + 4 + 220 + 2u);
  std::string err;
  const auto untagged = unpackBundles(plain, &err);
  ASSERT_TRUE(untagged) << err;
  EXPECT_EQ((*untagged)[1].data, b);
  EXPECT_TRUE((*untagged)[1].tags.empty());
  const auto got = unpackBundles(pack, &err);
  ASSERT_TRUE(got) << err;
  ASSERT_EQ(got->size(), 3u);
  EXPECT_EQ((*got)[0].data, a);
  EXPECT_EQ((*got)[1].data, b);
  EXPECT_EQ((*got)[2].data, c);
  EXPECT_EQ((*got)[1].tags, tags);
  EXPECT_TRUE((*got)[0].tags.empty());
  const Bytes other = {2, 1}, none;
  EXPECT_THROW(packBundles({&a, &other}), std::invalid_argument);
  EXPECT_THROW(packBundles({&a, &none}), std::invalid_argument);
  EXPECT_THROW(packBundles({}), std::invalid_argument);
  auto rejects = [](const Bytes& data, const std::string& what) {
    std::string e;
    EXPECT_FALSE(unpackBundles(data, &e));
    EXPECT_NE(e.find(what), std::string::npos) << e;
  };
  rejects({}, "truncated");
  rejects({3, 0}, "bundle count 0 out of range");
  rejects({3, 6, 1, 9}, "bundle count 3 out of range");
  rejects({3, 2, 5, 1, 2}, "bundle 0 length 5 exceeds");
  rejects({3, 2, 1, 9, 9}, "1 trailing bytes");
  rejects({3, 3, 1, 9, 5, 1}, "bundle 0 tag length 5 out of range");
  for (std::size_t n = 0; n < pack.size(); ++n) EXPECT_FALSE(unpackBundles(Bytes(pack.begin(), pack.begin() + n), &err));
}
