#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "simulator/drifted_object_map.h"

using namespace slide;

namespace {
place::Landmark object(int cls, double x, double y, double z, const Eigen::Vector3d& size) {
  place::Landmark l;
  l.class_id = cls;
  l.p = {x, y, z};
  l.size = size;
  return l;
}

// Trunks, poles and cars scattered uniformly over [0, w] x [-h, h].
std::vector<place::Landmark> scatter(int n, double w, double h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(0, w), y(-h, h), r(0.1, 0.4);
  std::vector<place::Landmark> out;
  for (int i = 0; i < n; ++i) {
    const int cls = i % 3 == 0 ? 10 : (i % 3 == 1 ? 71 : 80);
    const double d = 2 * r(rng);
    out.push_back(cls == 10 ? object(cls, x(rng), y(rng), 0.75, {4.5, 1.8, 1.5}) : object(cls, x(rng), y(rng), 0.0, {d, d, 3.0}));
    out.back().index = static_cast<std::size_t>(i);
  }
  return out;
}

// No drift, noise, misses, false objects or confusion.
simulator::MapErrorParams exact() {
  simulator::MapErrorParams p;
  p.yaw_drift_deg_per_100m = p.scale_error = p.vertical_drift_per_100m = 0;
  p.position_sigma = p.size_sigma = 0;
  p.missed = p.spurious = p.confusion = 0;
  return p;
}

double sumSquares(const std::vector<place::Landmark>& a, const std::vector<place::Landmark>& b, const Pose& T) {
  double sum = 0;
  for (const place::Landmark& la : a)
    for (const place::Landmark& lb : b)
      if (la.index == lb.index && la.index != simulator::kSpuriousObject) sum += (la.p - T * lb.p).squaredNorm();
  return sum;
}
}  // namespace

TEST(DriftedObjectMap, PosesFollowTheRouteAtTheStep) {
  const std::vector<Pose> poses = simulator::posesAlong({{0, 0}, {10, 0}, {10, 5.2}}, 0.5);
  ASSERT_EQ(poses.size(), 32u);  // 0..9.5 on x, 10,0 .. 10,5 on y, and the end
  EXPECT_NEAR(poses[20].translation().x(), 10.0, 1e-9);
  EXPECT_NEAR(poses[20].translation().y(), 0.0, 1e-9);
  EXPECT_NEAR(yawOf(poses[20].linear()), M_PI / 2, 1e-9);
  EXPECT_NEAR(poses.back().translation().y(), 5.2, 1e-9);
  EXPECT_TRUE(simulator::posesAlong({{1, 1}, {1, 1}}, 0.5).empty());
}

TEST(DriftedObjectMap, YawAndHeightDriftGrowAsConfigured) {
  simulator::MapErrorParams p = exact();
  p.yaw_drift_deg_per_100m = 1.5;
  p.vertical_drift_per_100m = 0.3;
  p.range = 5;
  // One pole 2 m left of a straight 200 m route, passed at 150 m.
  std::vector<place::Landmark> world{object(80, 150, 2, 0, {0.3, 0.3, 4})};
  std::mt19937 rng(3);
  const simulator::DriftedMap m = simulator::mapAlongRoute(world, {{0, 0}, {200, 0}}, p, {}, rng);
  const double b = m.yaw_rate;
  ASSERT_NEAR(std::abs(b), 1.5 * M_PI / 180 / 100, 1e-12);
  // Heading and height error at the end: rate times distance.
  EXPECT_NEAR(yawOf(m.odometry.back().linear()), b * 200, 1e-6);
  EXPECT_NEAR(std::abs(m.odometry.back().translation().z()), 0.6, 1e-6);
  // Position at the end: the arc of a constant yaw-rate error.
  EXPECT_NEAR(m.odometry.back().translation().x(), std::sin(b * 200) / b, 0.05);
  EXPECT_NEAR(m.odometry.back().translation().y(), (1 - std::cos(b * 200)) / b, 0.05);
  // The pole is placed from the drifted pose at 150 m: bent away from its true (0-drift) place.
  ASSERT_EQ(m.lms.size(), 1u);
  const double s = 150;
  const Eigen::Vector2d expected(std::sin(b * s) / b - 2 * std::sin(b * s), (1 - std::cos(b * s)) / b + 2 * std::cos(b * s));
  EXPECT_NEAR(m.lms[0].p.x(), expected.x(), 0.05);
  EXPECT_NEAR(m.lms[0].p.y(), expected.y(), 0.05);
  EXPECT_NEAR(std::abs(m.lms[0].p.z()), 0.45, 1e-6);
  EXPECT_GT((m.lms[0].p.head<2>() - Eigen::Vector2d(150, 2)).norm(), 2.5);  // 1.5 deg/100 m bends it ~3 m
  EXPECT_NEAR(m.seen_at[0], 150, 1e-9);
}

TEST(DriftedObjectMap, WithoutErrorsTheMapIsTheWorldInTheStartFrame) {
  const std::vector<place::Landmark> world = scatter(400, 200, 30, 1);
  std::mt19937 rng(4);
  const simulator::DriftedMap m = simulator::mapAlongRoute(world, {{20, 5}, {180, -5}}, exact(), {}, rng);
  ASSERT_GT(m.lms.size(), 150u);
  for (const place::Landmark& l : m.lms) EXPECT_LT((m.T_w_r * l.p - world[l.index].p).norm(), 1e-9);
}

TEST(DriftedObjectMap, MissedSpuriousAndConfusionRatesMatchTheConfiguration) {
  const std::vector<place::Landmark> world = scatter(30000, 1000, 25, 2);
  simulator::MapErrorParams p = exact();
  p.range = 15;
  p.missed = 0.2;
  p.spurious = 0.2;
  p.confusion = 0.1;
  const simulator::ClassConfusions conf{{71, {80}}, {80, {71}}, {10, {0}}};
  const std::vector<Eigen::Vector2d> route{{0, 0}, {1000, 0}};
  std::size_t seen = 0;
  for (const place::Landmark& l : world) seen += std::abs(l.p.y()) <= 15;
  std::mt19937 rng(5);
  const simulator::DriftedMap m = simulator::mapAlongRoute(world, route, p, conf, rng);
  std::size_t mapped = 0, spurious = 0, confused = 0;
  for (std::size_t i = 0; i < m.lms.size(); ++i) {
    const place::Landmark& l = m.lms[i];
    if (l.index == simulator::kSpuriousObject) {
      ++spurious;
      // Plausible: a class of the world with the size of one of its objects (within 4 sigma of 15 %).
      EXPECT_TRUE(l.class_id == 10 || l.class_id == 71 || l.class_id == 80 || l.class_id == 0) << l.class_id;
      const bool car = m.true_class[i] == 10;
      EXPECT_LT(l.size.z(), (car ? 1.5 : 3.0) * 1.61);
      EXPECT_GT(l.size.z(), (car ? 1.5 : 3.0) * 0.39);
      EXPECT_LE(std::abs(l.p.y()), 15.0 + 1e-9);  // within range of the route (no drift here)
      continue;
    }
    ++mapped;
    confused += l.class_id != m.true_class[i];
    EXPECT_EQ(m.true_class[i], world[l.index].class_id);
  }
  ASSERT_GT(seen, 5000u);
  EXPECT_NEAR(double(mapped) / seen, 0.8, 0.02);
  EXPECT_NEAR(double(spurious) / mapped, 0.2, 0.02);
  EXPECT_NEAR(double(confused) / mapped, 0.1, 0.015);
}

TEST(DriftedObjectMap, TruthIsTheLeastSquaresTransformOverSharedObjects) {
  const std::vector<place::Landmark> world = scatter(3000, 400, 20, 3);
  simulator::MapErrorParams p;  // drift, noise, misses, false objects, confusion
  p.range = 15;
  std::mt19937 rng(6);
  const simulator::DriftedMap a = simulator::mapAlongRoute(world, {{0, 0}, {250, 0}}, p, {{71, {80}}}, rng);
  const simulator::DriftedMap b =
      simulator::mapAlongRoute(world, {{400, 3}, {150, -3}}, p, {{71, {80}}}, rng);  // opposite direction
  const simulator::SharedTruth t = simulator::sharedObjectTruth(a.lms, b.lms);
  ASSERT_TRUE(t.ok);
  std::set<std::size_t> ia, ib;
  for (const place::Landmark& l : a.lms)
    if (l.index != simulator::kSpuriousObject) ia.insert(l.index);
  std::size_t shared = 0;
  for (const place::Landmark& l : b.lms) shared += l.index != simulator::kSpuriousObject && ia.count(l.index);
  EXPECT_EQ(t.shared, shared);
  EXPECT_GT(shared, 50u);
  // A minimum of the squared residuals over the shared objects: every small step away costs.
  const double best = sumSquares(a.lms, b.lms, t.T_a_b);
  for (int k = 0; k < 4; ++k) {
    for (double sgn : {-1.0, 1.0}) {
      Eigen::Vector4d d = Eigen::Vector4d::Zero();
      d[k] = sgn * (k == 3 ? 1e-3 : 0.01);
      const Pose step = poseFromXyzYaw(d);
      EXPECT_GT(sumSquares(a.lms, b.lms, step * t.T_a_b), best);
    }
  }
  // Not the undistorted transform between the robots' frames: the maps are bent.
  const Pose undistorted = a.T_w_r.inverse() * b.T_w_r;
  const double undistorted_ss = sumSquares(a.lms, b.lms, undistorted);
  EXPECT_GT(undistorted_ss, 2 * best) << best;
  // False objects do not count, even one carrying a shared object's place.
  std::vector<place::Landmark> b2 = b.lms;
  place::Landmark fake = b2.front();
  fake.index = simulator::kSpuriousObject;
  fake.p += Eigen::Vector3d(50, 50, 5);
  b2.push_back(fake);
  const simulator::SharedTruth t2 = simulator::sharedObjectTruth(a.lms, b2);
  EXPECT_EQ(t2.shared, t.shared);
  EXPECT_LT((t2.T_a_b.matrix() - t.T_a_b.matrix()).norm(), 1e-12);
}

TEST(DriftedObjectMap, WithoutErrorsTheTruthIsTheTransformBetweenTheFrames) {
  const std::vector<place::Landmark> world = scatter(2000, 300, 20, 7);
  std::mt19937 rng(8);
  const simulator::DriftedMap a = simulator::mapAlongRoute(world, {{0, 0}, {200, 10}}, exact(), {}, rng);
  const simulator::DriftedMap b = simulator::mapAlongRoute(world, {{300, -10}, {100, 0}}, exact(), {}, rng);
  const simulator::SharedTruth t = simulator::sharedObjectTruth(a.lms, b.lms);
  ASSERT_TRUE(t.ok);
  EXPECT_LT((t.T_a_b.matrix() - (a.T_w_r.inverse() * b.T_w_r).matrix()).norm(), 1e-9);
  EXPECT_LT(t.rms, 1e-9);
  EXPECT_FALSE(simulator::sharedObjectTruth(a.lms, {}).ok);
}

TEST(DriftedObjectMap, TheMapAtAMomentHoldsWhatWasPlacedBefore) {
  const std::vector<place::Landmark> world = scatter(1000, 200, 20, 9);
  std::mt19937 rng(10);
  simulator::MapErrorParams p;
  const simulator::DriftedMap m = simulator::mapAlongRoute(world, {{0, 0}, {200, 0}}, p, {}, rng);
  const std::vector<place::Landmark> half = simulator::mapUpTo(m, 100);
  std::size_t expected = 0;
  for (double s : m.seen_at) expected += s <= 100;
  EXPECT_EQ(half.size(), expected);
  EXPECT_GT(half.size(), m.lms.size() / 3);
  EXPECT_LT(half.size(), 2 * m.lms.size() / 3);
  for (const place::Landmark& l : half) {
    if (l.index != simulator::kSpuriousObject) {
      EXPECT_LT(world[l.index].p.x(), 100 + p.range + 1e-9);
    }
  }
}
