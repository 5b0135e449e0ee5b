// The optimizer on small scenarios: incremental equals batch after a full solve, bad input is
// rejected with a reason and leaves the graph usable, and a peer merges through a transform.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>

#include "config/config.h"

#include "backend/optimizer.h"
#include "graph_scenario/scenario.h"

using namespace slide;

namespace {

// The indoor world, driven by two robots: robot 0 the first 90 key poses, robot 1 poses
// 60..149 (their paths overlap), each in its own odometry frame.
// With `third`, a third robot drives poses 30..119.
graph_scenario::GraphScenario twoRobotIndoor(bool third = false) {
  graph_scenario::GraphScenario s = graph_scenario::makeIndoorScenario(4);
  const std::vector<Pose> path = s.robots[0].truth;
  std::mt19937 rng(9);
  s.robots.clear();
  s.robots.push_back(graph_scenario::simulateRobot(0, {path.begin(), path.begin() + 90}, s.landmarks, s.noise, rng));
  s.robots.push_back(
      graph_scenario::simulateRobot(1, {path.begin() + 60, path.end()}, s.landmarks, s.noise, rng, 50000000));
  if (third)
    s.robots.push_back(
        graph_scenario::simulateRobot(2, {path.begin() + 30, path.begin() + 120}, s.landmarks, s.noise, rng, 90000000));
  return s;
}

// The robot's odometry reads every step `factor` times its length (a wheel radius set wrong).
void scaleOdometry(std::vector<KeyPoseBundle>& bundles, double factor) {
  Pose odom = Pose::Identity();
  for (std::size_t k = 0; k < bundles.size(); ++k) {
    if (k > 0) bundles[k].relative_odom.translation() *= factor;
    odom = k == 0 ? bundles[0].odom_pose : Pose(odom * bundles[k].relative_odom);
    bundles[k].odom_pose = odom;
  }
}

double maxTranslationGap(const std::vector<backend::TrajectoryPose>& a, const std::vector<backend::TrajectoryPose>& b) {
  double gap = 0;
  for (std::size_t i = 0; i < a.size(); ++i) gap = std::max(gap, (a[i].pose.translation() - b[i].pose.translation()).norm());
  return gap;
}

}  // namespace

TEST(BackendOptimizer, IncrementalEqualsBatchAfterFullSolve) {
  const graph_scenario::GraphScenario s = graph_scenario::makeIndoorScenario(1);
  backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  int full = 0;
  for (const KeyPoseBundle& b : s.robots[0].bundles) {
    const backend::UpdateResult r = opt.addBundle(b);
    ASSERT_TRUE(r.accepted) << r.reason;
    full += r.full_solve;
  }
  EXPECT_GE(full, 1);  // the lap closes: at least one full solve on the way
  opt.fullSolve();
  const backend::Optimizer::Batch batch = opt.solveBatch();
  EXPECT_NEAR(opt.cost(), batch.report.final_cost, 1e-6 * batch.report.final_cost);
  const auto inc = opt.trajectory(0);
  ASSERT_EQ(inc.size(), batch.trajectories.at(0).size());
  EXPECT_LT(maxTranslationGap(inc, batch.trajectories.at(0)), 1e-3);
  const auto lms = opt.landmarks();
  ASSERT_EQ(lms.size(), batch.landmarks.size());
  for (std::size_t i = 0; i < lms.size(); ++i) EXPECT_LT((lms[i].position() - batch.landmarks[i].position()).norm(), 1e-3);
  // Every true landmark is mapped once, close to the truth (the host frame is the world's
  // frame shifted by the first pose).
  EXPECT_NEAR(static_cast<double>(lms.size()), static_cast<double>(s.landmarks.size()), 3.0);
}

TEST(BackendOptimizer, KeyPosesNeverReceivedAreCounted) {
  const graph_scenario::GraphScenario s = graph_scenario::makeIndoorScenario(2);
  const auto& in = s.robots[0].bundles;
  backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  for (int k = 0; k < 5; ++k) ASSERT_TRUE(opt.addBundle(in[k]).accepted);
  EXPECT_EQ(opt.missingKeyPoses(), 0);
  // A flood the daemon could not keep up with: it saw only every 10th bundle.
  for (int k = 10; k < 60; k += 10) ASSERT_TRUE(opt.addBundle(in[k]).accepted);
  EXPECT_EQ(opt.missingKeyPoses(), 5 + 4 * 9);
  EXPECT_EQ(opt.numKeyPoses(), 10);
}

TEST(BackendOptimizer, RejectsBadInputAndStaysConsistent) {
  const graph_scenario::GraphScenario s = graph_scenario::makeIndoorScenario(2);
  const auto& in = s.robots[0].bundles;
  backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  for (int k = 0; k < 10; ++k) ASSERT_TRUE(opt.addBundle(in[k]).accepted);
  const int poses = opt.numKeyPoses();

  KeyPoseBundle nan = in[10];
  nan.relative_odom.translation().x() = std::nan("");
  backend::UpdateResult r = opt.addBundle(nan);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("non-finite"), std::string::npos) << r.reason;

  KeyPoseBundle jump = in[10];
  jump.relative_odom.translation() += Eigen::Vector3d(500, 0, 0);
  r = opt.addBundle(jump);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("odometry jump"), std::string::npos) << r.reason;

  r = opt.addBundle(in[9]);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("duplicate key pose"), std::string::npos) << r.reason;

  KeyPoseBundle early = in[10];
  early.utime = in[9].utime - 1;
  r = opt.addBundle(early);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("timestamp out of order"), std::string::npos) << r.reason;
  EXPECT_EQ(opt.numKeyPoses(), poses);
  EXPECT_EQ(opt.rejected(), 4);

  // Bad objects are dropped with a warning; the rest of the bundle is used.
  KeyPoseBundle mixed = in[10];
  ASSERT_GE(mixed.objects.size(), 2u);
  mixed.objects[0].class_id = 999;
  std::get<Ellipsoid>(mixed.objects[1].model).centroid.y() = INFINITY;
  r = opt.addBundle(mixed);
  ASSERT_TRUE(r.accepted) << r.reason;
  ASSERT_EQ(r.warnings.size(), 2u);
  EXPECT_NE(r.warnings[0].find("unknown class"), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[1].find("non-finite"), std::string::npos) << r.warnings[1];
  EXPECT_EQ(r.landmark_ids[0], -1);
  EXPECT_EQ(r.landmark_ids[1], -1);
  EXPECT_GE(r.landmark_ids[2], 0);

  // A missing key pose is bridged with the odometry poses; the graph keeps working.
  r = opt.addBundle(in[12]);
  ASSERT_TRUE(r.accepted) << r.reason;
  EXPECT_EQ(opt.numKeyPoses(), poses + 2);
  EXPECT_FALSE(opt.addLoopClosure(0, 3, 77, Pose::Identity()).accepted);
  opt.fullSolve();
  EXPECT_TRUE(std::isfinite(opt.cost()));
  EXPECT_LT((opt.trajectory(0).back().pose.translation() -
             (s.robots[0].truth[0].inverse() * s.robots[0].truth[12]).translation()).norm(), 0.2);
}

TEST(BackendOptimizer, MergesPeerThroughTransformAndRefinesWithoutDuplicating) {
  const graph_scenario::GraphScenario s = twoRobotIndoor();
  backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  const auto& a = s.robots[0].bundles;
  const auto& b = s.robots[1].bundles;
  for (const auto& x : a) ASSERT_TRUE(opt.addBundle(x).accepted);
  for (std::size_t k = 0; k < 40; ++k) {
    const backend::UpdateResult r = opt.addBundle(b[k]);
    ASSERT_TRUE(r.accepted);
    EXPECT_TRUE(r.held);
  }
  EXPECT_EQ(opt.numHeld(), 40);
  EXPECT_EQ(opt.robots(), (std::vector<int>{0}));
  const int landmarks_before = opt.numLandmarks(false);

  const Pose truth = s.robots[0].truth[0].inverse() * s.robots[1].truth[0];
  const backend::UpdateResult m = opt.addRobotTransform(1, truth * poseFromXyzYaw(0.2, -0.1, 0, 0.01));
  ASSERT_TRUE(m.accepted);
  EXPECT_TRUE(m.full_solve);
  EXPECT_EQ(opt.numHeld(), 0);
  EXPECT_EQ(opt.robots(), (std::vector<int>{0, 1}));
  for (std::size_t k = 40; k < b.size(); ++k) ASSERT_TRUE(opt.addBundle(b[k]).accepted);
  const std::size_t factors = opt.graph().numFactors();
  opt.addRobotTransform(1, truth);  // refinement replaces the anchor
  EXPECT_EQ(opt.graph().numFactors(), factors);
  opt.fullSolve();

  // Shared objects are one landmark: the peer adds only what robot 0 never saw.
  std::vector<char> seen0(s.landmarks.size(), 0), seen_any(s.landmarks.size(), 0);
  for (const auto& list : s.robots[0].seen)
    for (int i : list) seen0[i] = seen_any[i] = 1;
  for (const auto& list : s.robots[1].seen)
    for (int i : list) seen_any[i] = 1;
  const int new_objects = std::count(seen_any.begin(), seen_any.end(), 1) - std::count(seen0.begin(), seen0.end(), 1);
  EXPECT_LE(opt.numLandmarks(false) - landmarks_before, new_objects + 3);

  // The peer's trajectory lands where it truly was, in the host's frame.
  const auto peer = opt.trajectory(1);
  ASSERT_EQ(peer.size(), b.size());
  double worst = 0;
  for (const auto& p : peer)
    worst = std::max(worst, (p.pose.translation() -
                             (s.robots[0].truth[0].inverse() * s.robots[1].truth[p.seq]).translation()).norm());
  EXPECT_LT(worst, 0.3);
}

TEST(BackendConfig, LoadsShippedFileAndNamesBadKeys) {
  const backend::BackendConfig c = backend::loadBackendConfig(std::string(SLIDE_SOURCE_DIR) + "/config/backend.yaml");
  EXPECT_EQ(c.min_observations, 3);
  EXPECT_DOUBLE_EQ(c.bearing_sigma, 0.05);
  const std::string bad = ::testing::TempDir() + "/bad_backend.yaml";
  auto expectError = [&](const std::string& yaml, const std::string& key) {
    {
      std::ofstream out(bad);
      out << yaml;
    }
    try {
      backend::loadBackendConfig(bad);
      FAIL() << "expected a ConfigError for " << key;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad_backend.yaml"), std::string::npos) << e.what();
    }
  };
  expectError("objects:\n  range_sigma: -1\n", "range_sigma");
  expectError("odometry:\n  scale_sigma: 0.7\n", "scale_sigma");
  expectError("association:\n  revisit_sigmas: -1\n", "revisit_sigmas");
  EXPECT_DOUBLE_EQ(c.revisit_sigmas, 2.0);
}

// Issue 15, urban: a peer merged through an aliased transform (a half turn of the scene, as a
// periodic block grid gives) and later the right transform. The peer is un-merged and merged
// again: its key poses land where they truly were, the host's own trajectory is as if the
// wrong merge had never happened.
TEST(BackendOptimizer, AliasedMergeIsUndoneWhenTheRightTransformArrives) {
  const graph_scenario::GraphScenario s = twoRobotIndoor();
  const auto& a = s.robots[0].bundles;
  const auto& b = s.robots[1].bundles;
  backend::Optimizer solo(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  for (const auto& x : a) ASSERT_TRUE(solo.addBundle(x).accepted);
  solo.fullSolve();

  backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  for (const auto& x : a) ASSERT_TRUE(opt.addBundle(x).accepted);
  for (std::size_t k = 0; k < 40; ++k) ASSERT_TRUE(opt.addBundle(b[k]).accepted);
  const Pose truth = s.robots[0].truth[0].inverse() * s.robots[1].truth[0];
  const Pose alias = poseFromXyzYaw(12.0, 8.0, 0, M_PI) * truth;
  ASSERT_TRUE(opt.addRobotTransform(1, alias).accepted);
  for (std::size_t k = 40; k < b.size(); ++k) ASSERT_TRUE(opt.addBundle(b[k]).accepted);
  const backend::UpdateResult r = opt.addRobotTransform(1, truth);
  ASSERT_TRUE(r.accepted);
  opt.fullSolve();
  EXPECT_GE(opt.unmerged(), 1);
  ASSERT_TRUE(opt.merged(1));

  const auto peer = opt.trajectory(1);
  ASSERT_EQ(peer.size(), b.size());
  double worst = 0;
  for (const auto& p : peer)
    worst = std::max(worst, (p.pose.translation() -
                             (s.robots[0].truth[0].inverse() * s.robots[1].truth[p.seq]).translation()).norm());
  EXPECT_LT(worst, 0.3);
  const auto own = opt.trajectory(0), own_solo = solo.trajectory(0);
  ASSERT_EQ(own.size(), own_solo.size());
  EXPECT_LT(maxTranslationGap(own, own_solo), 0.3);
}

// Issue 15, indoor: an intra-robot loop closure between look-alike rooms (10 m and a quarter
// turn away from what odometry says) is refused; the true one is taken.
TEST(BackendOptimizer, LoopClosureOutsideTheOdometryEnvelopeIsRefused) {
  const graph_scenario::GraphScenario s = twoRobotIndoor();
  backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  for (const auto& x : s.robots[0].bundles) ASSERT_TRUE(opt.addBundle(x).accepted);
  const Pose true_0_50 = s.robots[0].truth[0].inverse() * s.robots[0].truth[50];
  const backend::UpdateResult wrong = opt.addLoopClosure(0, 0, 50, poseFromXyzYaw(10.0, 3.0, 0, M_PI / 2) * true_0_50);
  EXPECT_FALSE(wrong.accepted);
  EXPECT_NE(wrong.reason.find("implausible loop closure"), std::string::npos) << wrong.reason;
  EXPECT_TRUE(opt.addLoopClosure(0, 0, 50, true_0_50).accepted);
  const auto own = opt.trajectory(0);
  double worst = 0;
  for (const auto& p : own)
    worst = std::max(worst, (p.pose.translation() -
                             (s.robots[0].truth[0].inverse() * s.robots[0].truth[p.seq]).translation()).norm());
  EXPECT_LT(worst, 0.5);
}

TEST(BackendOptimizer, RefinementsStopMovingAPeerOnceSharedLandmarksAlignIt) {
  // Place recognition keeps re-detecting a merged peer's transform from maps that already hold
  // the merge; once the two robots share landmarks in the graph, such a refinement is the same
  // observations counted twice, and it leaves the estimate alone. Before that it moves the anchor.
  const graph_scenario::GraphScenario s = twoRobotIndoor();
  const Pose truth = s.robots[0].truth[0].inverse() * s.robots[1].truth[0];
  const Pose off = truth * poseFromXyzYaw(0.8, -0.5, 0, 0.03);  // within the remerge limits
  for (int until : {1000000, 10}) {
    backend::BackendConfig cfg;
    cfg.refine_until_shared = until;
    backend::Optimizer opt(cfg, ClassTable::loadDefault(), 0);
    for (const auto& x : s.robots[0].bundles) ASSERT_TRUE(opt.addBundle(x).accepted);
    for (const auto& x : s.robots[1].bundles) ASSERT_TRUE(opt.addBundle(x).accepted);
    ASSERT_TRUE(opt.addRobotTransform(1, truth).accepted);
    opt.fullSolve();
    ASSERT_GE(opt.sharedLandmarks(1), 10);
    const Pose before = opt.trajectory(1).front().pose;
    const backend::UpdateResult r = opt.addRobotTransform(1, off);
    EXPECT_TRUE(r.accepted);
    opt.fullSolve();
    const double moved = (opt.trajectory(1).front().pose.translation() - before.translation()).norm();
    if (until == 10) {
      EXPECT_FALSE(r.full_solve);
      EXPECT_LT(moved, 1e-3) << "a refinement moved a peer the shared landmarks already align";
    } else {
      EXPECT_TRUE(r.full_solve) << "with refinements always taken the anchor is replaced (the test's control)";
    }
  }
}

namespace {
// An ellipsoid detection of `class_id` at body position p; ids index the bundle's objects.
Object ellipsoidAt(int id, int class_id, const Eigen::Vector3d& p, double radius, double height) {
  Object o;
  o.id = id;
  o.class_id = class_id;
  o.model = Ellipsoid{p, radius, height};
  return o;
}

// Key pose k of a robot driving along x, 0.5 m per key pose, with exact odometry.
KeyPoseBundle stepBundle(int k, std::vector<Object> objects) {
  KeyPoseBundle b;
  b.seq = k;
  b.utime = k * 100000;
  b.odom_pose = poseFromXyzYaw(0.5 * k, 0, 0, 0);
  b.relative_odom = k ? poseFromXyzYaw(0.5, 0, 0, 0) : Pose::Identity();
  b.objects = std::move(objects);
  return b;
}

// stepBundle whose odometry slips `slip` m sideways at key pose `at` (and says so: a 5 m sigma);
// every other step is told with a tight sigma.
KeyPoseBundle slippedBundle(int k, std::vector<Object> objects, int at, double slip) {
  KeyPoseBundle b = stepBundle(k, std::move(objects));
  b.odom_pose = poseFromXyzYaw(0.5 * k, k < at ? 0.0 : slip, 0, 0);
  if (k == at) b.relative_odom = poseFromXyzYaw(0.5, slip, 0, 0);
  b.odom_sigma << 0.005, 0.005, 0.005, 0.0005, 0.0005, 0.0005;
  if (k == at) b.odom_sigma.head<3>().setConstant(5.0);
  return b;
}

// A chair at (6, 2) beside a table 0.8 m away, both seen from 14 key poses; the chair is
// reported as a table at key poses 3, 7 and 11. With `clutter`, key pose 13 also reports a false
// table 0.3 m from the chair (a bin), which joins the confused detections' landmark.
std::vector<Object> chairBesideTable(const backend::BackendConfig& cfg, bool clutter) {
  const int chair = 1, table = 2;
  backend::Optimizer opt(cfg, ClassTable::loadDefault(), 0);
  for (int k = 0; k < 14; ++k) {
    const Eigen::Vector3d o(0.5 * k, 0, 0);
    const bool confused = k % 4 == 3;
    std::vector<Object> seen{ellipsoidAt(0, confused ? table : chair, Eigen::Vector3d(6, 2, 0.45) - o, 0.3, 0.9),
                             ellipsoidAt(1, table, Eigen::Vector3d(6.8, 2, 0.4) - o, 0.7, 0.8)};
    if (clutter && k == 13) seen.push_back(ellipsoidAt(2, table, Eigen::Vector3d(6, 1.7, 0.45) - o, 0.3, 0.9));
    const backend::UpdateResult r = opt.addBundle(stepBundle(k, seen));
    EXPECT_TRUE(r.accepted) << r.reason;
  }
  opt.fullSolve();
  return opt.landmarks();
}
}  // namespace

// Issue 20: a detector that now and then takes a chair for a table makes a second landmark of
// that chair (association keeps classes apart). After a full solve it is merged into the chair
// (never seen from the chair's key poses, at the chair); the real table 0.8 m away, in view
// with the chair every time, stays a landmark of its own.
TEST(BackendOptimizer, MergesAConfusedClassIntoItsObjectButNotTheObjectBesideIt) {
  backend::BackendConfig apart;
  apart.merge_within_shape = false;
  EXPECT_EQ(chairBesideTable(apart, false).size(), 3u);  // the confused detections' landmark is confirmed
  const std::vector<Object> lms = chairBesideTable(backend::BackendConfig{}, false);
  ASSERT_EQ(lms.size(), 2u);
  std::map<int, Eigen::Vector3d> by_class;
  for (const Object& lm : lms) by_class[lm.class_id] = lm.position();
  ASSERT_EQ(by_class.count(1), 1u);
  ASSERT_EQ(by_class.count(2), 1u);
  EXPECT_LT((by_class[1] - Eigen::Vector3d(6, 2, 0.45)).norm(), 0.05);
  EXPECT_LT((by_class[2] - Eigen::Vector3d(6.8, 2, 0.4)).norm(), 0.05);
}

// A LiDAR robot without labels sees a chair as "other" from key poses 0-9; key poses 10-13 (a
// detector, e.g. a merged peer's) name it a chair. The two landmarks are merged and the votes
// decide the class: label-free "other" votes at the geometric segmenter's other_confidence
// (0.05) yield to the named ones; at full weight the ten "other" votes win.
TEST(BackendOptimizer, AnUnnamedObjectTakesTheClassADetectorGivesIt) {
  const int other = 0, chair = 1;
  for (const float other_confidence : {0.05f, 1.0f}) {
    backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
    for (int k = 0; k < 14; ++k) {
      Object o = ellipsoidAt(0, k < 10 ? other : chair, Eigen::Vector3d(6, 2, 0.45) - Eigen::Vector3d(0.5 * k, 0, 0), 0.3, 0.9);
      o.confidence = k < 10 ? other_confidence : 0.8f;
      ASSERT_TRUE(opt.addBundle(stepBundle(k, {o})).accepted);
    }
    opt.fullSolve();
    const std::vector<Object> lms = opt.landmarks();
    ASSERT_EQ(lms.size(), 1u) << other_confidence;
    EXPECT_EQ(lms[0].class_id, other_confidence < 0.5f ? chair : other) << other_confidence;
  }
}

// A row of cars parked nose in (along y, 2.6 m apart) seen whole from key poses 0-5; the next
// car in the row is seen from key poses 6-11 only by its end face, which the front-end read as
// a car across (centre 1.35 m to the side and 1.5 m short) with the right box as the other
// reading. Its landmark has no whole view to choose by, but the map's parallel neighbours
// settle the reading: the landmark stands on the car, along y. With reading_vote_radius 0 it
// keeps the front-end's reading, across.
TEST(BackendOptimizer, ABoxReadTwoWaysTakesTheReadingItsParkedNeighboursAgreeWith) {
  auto carAt = [](const Pose& T_body_world, double x, double y, double yaw) {
    Object o;
    o.class_id = 10;
    o.model = Cuboid{T_body_world * poseFromXyzYaw(x, y, 0.75, yaw), {4.5, 1.8, 1.5}};
    return o;
  };
  auto run = [&](double radius) {
    backend::BackendConfig cfg;
    cfg.reading_vote_radius = radius;
    backend::Optimizer opt(cfg, ClassTable::loadDefault(), 0);
    for (int k = 0; k < 12; ++k) {
      const Pose T_body_world = poseFromXyzYaw(0.5 * k, 0, 0, 0).inverse();
      std::vector<Object> seen;
      for (int c = 0; c < 3; ++c) {
        seen.push_back(carAt(T_body_world, 2.6 * c, 6, M_PI / 2));
        seen.back().id = c;
      }
      if (k >= 6) {
        Object face = carAt(T_body_world, 7.8 + 1.35, 6 - 1.5, 0);
        face.id = 3;
        face.other_reading = std::get<Cuboid>(carAt(T_body_world, 7.8, 6, M_PI / 2).model);
        seen.push_back(face);
      }
      const backend::UpdateResult r = opt.addBundle(stepBundle(k, seen));
      EXPECT_TRUE(r.accepted) << r.reason;
    }
    opt.fullSolve();
    double best = 1e9;
    for (const Object& lm : opt.landmarks()) best = std::min(best, (lm.position() - Eigen::Vector3d(7.8, 6, 0.75)).head<2>().norm());
    return best;
  };
  EXPECT_GT(backend::BackendConfig{}.reading_vote_radius, 0) << "on by default";
  EXPECT_LT(run(backend::BackendConfig{}.reading_vote_radius), 0.05);
  EXPECT_GT(run(0), 1.0);
}

// A car along y at (6, 3), seen whole from key poses 0-7; from key poses 8-15 only its end
// face, which the front-end read as a car across (its centre 1.35 m to the side) with the
// right box as the other reading. The landmark keeps the reading it agrees with and stays on
// the car; without the other reading it is pulled off it.
TEST(BackendOptimizer, ABoxReadTwoWaysJoinsItsLandmarkAsTheReadingThatFits) {
  const Pose truth = poseFromXyzYaw(6, 3, 0.75, M_PI / 2);
  auto run = [&](bool with_other) {
    backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
    for (int k = 0; k < 16; ++k) {
      const Pose T_body_world = poseFromXyzYaw(0.5 * k, 0, 0, 0).inverse();
      Object o;
      o.id = 0;
      o.class_id = 10;
      o.model = Cuboid{T_body_world * truth, {4.5, 1.8, 1.5}};
      if (k >= 8) {
        const Cuboid whole = std::get<Cuboid>(o.model);
        o.model = Cuboid{T_body_world * poseFromXyzYaw(6 + 1.35, 3 - 1.5, 0.75, 0), {4.5, 1.8, 1.5}};
        if (with_other) o.other_reading = whole;
      }
      const backend::UpdateResult r = opt.addBundle(stepBundle(k, {o}));
      EXPECT_TRUE(r.accepted) << r.reason;
    }
    opt.fullSolve();
    const std::vector<Object> lms = opt.landmarks();
    double best = 1e9;
    for (const Object& lm : lms) best = std::min(best, (lm.position() - truth.translation()).head<2>().norm());
    return best;
  };
  EXPECT_LT(run(true), 0.05);
  EXPECT_GT(run(false), 0.3);
  // A second box far from the first, or of no car's size (which would also let it stand
  // anywhere), is no reading of it: dropped and named, the object kept.
  backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  Object far, huge, flat;
  for (Object* o : {&far, &huge, &flat}) {
    o->class_id = 10;
    o->model = Cuboid{truth, {4.5, 1.8, 1.5}};
  }
  far.other_reading = Cuboid{poseFromXyzYaw(40, 3, 0.75, 0), {4.5, 1.8, 1.5}};
  huge.other_reading = Cuboid{poseFromXyzYaw(40, 3, 0.75, 0), {1e6, 1.8, 1.5}};
  flat.other_reading = Cuboid{truth, {4.5, -1.8, 1.5}};
  const backend::UpdateResult r = opt.addBundle(stepBundle(0, {far, huge, flat}));
  ASSERT_TRUE(r.accepted) << r.reason;
  ASSERT_EQ(r.warnings.size(), 3u);
  for (const std::string& w : r.warnings) EXPECT_NE(w.find("inconsistent readings"), std::string::npos) << w;
  for (int k = 0; k < 3; ++k) EXPECT_GE(r.landmark_ids.at(k), 0);
}

// A chair at (6, 2) seen from key poses 0-11. At key pose 6 the odometry slips 1.2 m sideways
// (and says so: a 5 m sigma), so key poses 6-11 place the chair 1.2 m off, beyond its gate: a
// second chair landmark. Key pose 8 also reports a false chair 0.5 m from the real one, which
// joins the first landmark (the second took the chair's detection). A loop closure 0-11 puts the
// key poses back: the two landmarks now stand on one another but share key pose 8. Of one class
// and inside one another, they are one chair; merge_shared_fraction 0 keeps them apart. The
// confused table of chairBesideTable shares key pose 13 with the chair in the same way, but two
// classes seen together are two objects (a chair under a table): it stays.
TEST(BackendOptimizer, MergesTwoLandmarksOfOneChairThatShareAKeyPose) {
  auto chairs = [](double shared_fraction) {
    backend::BackendConfig cfg;
    cfg.merge_shared_fraction = shared_fraction;
    // The slip's 5 m sigma (there so that the loop closure may undo it) would also keep the false
    // chair off the first landmark (revisit_sigmas: another chair stands within that drift).
    cfg.revisit_sigmas = 0;
    backend::Optimizer opt(cfg, ClassTable::loadDefault(), 0);
    for (int k = 0; k < 12; ++k) {
      const Eigen::Vector3d o(0.5 * k, 0, 0);
      std::vector<Object> seen{ellipsoidAt(0, 1, Eigen::Vector3d(6, 2, 0.45) - o, 0.3, 0.9)};
      if (k == 8) seen.push_back(ellipsoidAt(1, 1, Eigen::Vector3d(6, 1.5, 0.45) - o, 0.3, 0.9));
      const backend::UpdateResult r = opt.addBundle(slippedBundle(k, seen, 6, 1.2));
      EXPECT_TRUE(r.accepted) << r.reason;
    }
    EXPECT_EQ(opt.numLandmarks(false), 2) << "the slip was to make a second chair landmark";
    EXPECT_TRUE(opt.addLoopClosure(0, 0, 11, poseFromXyzYaw(5.5, 0, 0, 0)).accepted);
    opt.fullSolve();
    return opt.landmarks();
  };
  const std::vector<Object> merged = chairs(backend::BackendConfig{}.merge_shared_fraction);
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_LT((merged[0].position() - Eigen::Vector3d(6, 2, 0.45)).head<2>().norm(), 0.1);
  EXPECT_EQ(chairs(0.0).size(), 2u);
  EXPECT_EQ(chairBesideTable(backend::BackendConfig{}, true).size(), 3u);
}

// A chair (0.6 m across, 0.8 m tall) seen whole from key poses 0-6; from key poses 7-13 its back is
// hidden and only the seat (0.2 m tall, centred 0.25 m higher) is reported: 0.6 m shorter, more than
// the class's model difference, so the seat makes a landmark of its own. Lying whole within the
// chair, it is a part of it: the full solve merges the two.
TEST(BackendOptimizer, MergesAChairsSeatSeenAloneIntoTheChair) {
  backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  for (int k = 0; k < 14; ++k) {
    const Eigen::Vector3d o(0.5 * k, 0, 0);
    const Object seen = k < 7 ? ellipsoidAt(0, 1, Eigen::Vector3d(6, 2, 0.4) - o, 0.3, 0.8)
                              : ellipsoidAt(0, 1, Eigen::Vector3d(6, 2, 0.65) - o, 0.3, 0.2);
    ASSERT_TRUE(opt.addBundle(stepBundle(k, {seen})).accepted);
  }
  ASSERT_EQ(opt.numLandmarks(), 2) << "the seat was to make a landmark of its own";
  opt.fullSolve();
  const std::vector<Object> lms = opt.landmarks();
  ASSERT_EQ(lms.size(), 1u);
  EXPECT_LT((lms[0].position() - Eigen::Vector3d(6, 2, 0.4)).head<2>().norm(), 0.05);
}

// Two cars parked on either side of a street, 5 m apart (y = 5 and y = 0), seen 40 m off: the
// first from key poses 0-3, the second from 4-7. The detection's own slack (twice its bearing
// sigma, 0.05 rad x 40 m) would widen the car's 3 m threshold by 4 m and join the second car to
// the first's landmark; capped (the class table's association_max_slack, 0.5 m for cars) it gets
// its own.
TEST(BackendOptimizer, ACarFarOffIsNotJoinedToTheCarAcrossTheStreet) {
  const ClassTable shipped = ClassTable::loadDefault();
  ASSERT_GT(shipped.at(10).association_max_slack, 0);
  auto landmarksOf = [&](double max_slack) {
    ClassTable classes;
    for (int id : shipped.ids()) {
      ClassInfo c = shipped.at(id);
      if (id == 10) c.association_max_slack = max_slack;
      classes.add(c);
    }
    backend::Optimizer opt(backend::BackendConfig{}, classes, 0);
    std::set<std::int64_t> ids;
    for (int k = 0; k < 8; ++k) {
      const Pose T_body_world = poseFromXyzYaw(0.5 * k, 0, 0, 0).inverse();
      Object o;
      o.id = 0;
      o.class_id = 10;
      o.model = Cuboid{T_body_world * poseFromXyzYaw(40, k < 4 ? 5 : 0, 0.75, 0), {4.5, 1.8, 1.5}};
      const backend::UpdateResult r = opt.addBundle(stepBundle(k, {o}));
      EXPECT_TRUE(r.accepted) << r.reason;
      ids.insert(r.landmark_ids.at(0));
    }
    return ids.size();
  };
  EXPECT_EQ(landmarksOf(shipped.at(10).association_max_slack), 2u);
  EXPECT_EQ(landmarksOf(0.0), 1u) << "uncapped, the far car is taken for the one across the street";
}

// Two cars parked side by side, C at (12, 6) and A at (12, 2.5). Key poses 0-3 see C; at key
// pose 4 the odometry slips 3.5 m sideways (and says so: a 5 m sigma), so key poses 4-11 place
// A where C is and their detections join C's landmark. A loop closure 0-11 puts the key poses
// back; without the gate test the landmark then stands 2.8 m from C's detections and 0.6 m from
// A's, C's residuals 4.2-4.7 against the outlier limit of 12 (4 sigmas x sqrt(9)). C's detections
// no longer pass the association gate that admitted them (their boxes do not meet the
// landmark's): they are detached and make C's landmark again.
TEST(BackendOptimizer, DetectionsTheSolvedEstimatePutsOutsideTheirGateLeaveTheLandmark) {
  const Eigen::Vector3d car_c(12, 6, 0.75), car_a(12, 2.5, 0.75);
  backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  for (int k = 0; k < 12; ++k) {
    const Pose truth = poseFromXyzYaw(0.5 * k, 0, 0, 0);
    Object o;
    o.class_id = 10;
    o.model = Cuboid{truth.inverse() * poseFromXyzYaw((k < 4 ? car_c : car_a).x(), (k < 4 ? car_c : car_a).y(), 0.75, 0),
                     {4.5, 1.8, 1.5}};
    const backend::UpdateResult r = opt.addBundle(slippedBundle(k, {o}, 4, 3.5));
    ASSERT_TRUE(r.accepted) << r.reason;
  }
  ASSERT_EQ(opt.numLandmarks(false), 1) << "A's detections were to join C's landmark";
  ASSERT_TRUE(opt.addLoopClosure(0, 0, 11, poseFromXyzYaw(5.5, 0, 0, 0)).accepted);
  opt.fullSolve();
  EXPECT_LT((opt.trajectory(0).back().pose.translation() - Eigen::Vector3d(5.5, 0, 0)).norm(), 0.1);
  const std::vector<Object> lms = opt.landmarks();
  ASSERT_EQ(lms.size(), 2u);
  for (const Eigen::Vector3d& car : {car_c, car_a}) {
    double best = 1e9;
    for (const Object& lm : lms) best = std::min(best, (lm.position() - car).head<2>().norm());
    EXPECT_LT(best, 0.1) << "car at " << car.transpose();
  }
}

// Issue 20 (forest realistic seed 5: before its first loop closure the drifted robot joined the
// trees of its start to their neighbours, and the closure then bent the loop 12 m). Ten chairs
// stand in a row 0.9 m apart along y = 2; the robot drives along x (0.5 m per key pose, sees the
// chairs within 4 m). Between key poses 9 and 10 its odometry jumps 0.9 m ahead and says it may
// have (a 0.5 m sigma): from then on each chair is placed exactly on its neighbour. Nearness cannot
// tell which chair is which within that drift, so by default none of the chairs seen before is
// taken again: new landmarks, until a loop closure 0-19 ties the two stretches; the full solve
// then puts the key poses back and merges each chair's two landmarks. With revisit_sigmas 0 the
// detections join the neighbouring chairs, which hold the jump against the closure.
TEST(BackendOptimizer, ARevisitBeyondTheOdometryDriftWaitsForTheLoopClosure) {
  constexpr int kChairs = 10;
  struct Run {
    int before_closure = 0, after = 0;
    double end_error_m = 0, worst_chair_m = 0;
  };
  auto run = [&](double revisit_sigmas) {
    backend::BackendConfig cfg;
    cfg.revisit_sigmas = revisit_sigmas;
    backend::Optimizer opt(cfg, ClassTable::loadDefault(), 0);
    for (int k = 0; k < 20; ++k) {
      const double x = 0.5 * k;
      std::vector<Object> seen;
      for (int c = 0; c < kChairs; ++c)
        if (std::abs(1.0 + 0.9 * c - x) < 4.0)
          seen.push_back(ellipsoidAt(static_cast<int>(seen.size()), 1, Eigen::Vector3d(1.0 + 0.9 * c - x, 2, 0.45), 0.3, 0.9));
      KeyPoseBundle b = stepBundle(k, seen);
      b.odom_pose = poseFromXyzYaw(x + (k >= 10 ? 0.9 : 0.0), 0, 0, 0);
      if (k == 10) b.relative_odom = poseFromXyzYaw(1.4, 0, 0, 0);
      b.odom_sigma << 0.005, 0.005, 0.005, 0.0005, 0.0005, 0.0005;
      if (k == 10) b.odom_sigma.head<3>().setConstant(0.5);
      const backend::UpdateResult r = opt.addBundle(b);
      EXPECT_TRUE(r.accepted) << r.reason;
    }
    Run out;
    out.before_closure = opt.numLandmarks(false);
    EXPECT_TRUE(opt.addLoopClosure(0, 0, 19, poseFromXyzYaw(9.5, 0, 0, 0)).accepted);
    opt.fullSolve();
    out.after = opt.numLandmarks(false);
    out.end_error_m = (opt.trajectory(0).back().pose.translation() - Eigen::Vector3d(9.5, 0, 0)).norm();
    for (int c = 0; c < kChairs; ++c) {
      double best = 1e9;
      for (const Object& lm : opt.landmarks(false))
        best = std::min(best, (lm.position() - Eigen::Vector3d(1.0 + 0.9 * c, 2, 0.45)).head<2>().norm());
      out.worst_chair_m = std::max(out.worst_chair_m, best);
    }
    return out;
  };
  const Run held = run(backend::BackendConfig{}.revisit_sigmas);
  EXPECT_GT(held.before_closure, kChairs) << "the chairs seen again after the jump were to make new landmarks";
  EXPECT_EQ(held.after, kChairs);
  EXPECT_LT(held.end_error_m, 0.1);
  EXPECT_LT(held.worst_chair_m, 0.1);
  const Run joined = run(0.0);
  EXPECT_EQ(joined.before_closure, kChairs + 1)
      << "without the rule each chair was to be taken for its neighbour (the last, with none, a new landmark)";
  EXPECT_GT(std::max(joined.end_error_m, joined.worst_chair_m), 0.3);
}

// A chair alone of its kind is still known after the same jump: the robot's detections join it.
TEST(BackendOptimizer, AnObjectAloneOfItsKindWithinTheDriftIsSeenAgain) {
  backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  for (int k = 0; k < 20; ++k) {
    const double x = 0.5 * k;
    KeyPoseBundle b = stepBundle(k, {ellipsoidAt(0, 1, Eigen::Vector3d(5.0 - x, 2, 0.45), 0.3, 0.9)});
    b.odom_pose = poseFromXyzYaw(x + (k >= 10 ? 0.4 : 0.0), 0, 0, 0);
    if (k == 10) b.relative_odom = poseFromXyzYaw(0.9, 0, 0, 0);
    b.odom_sigma << 0.005, 0.005, 0.005, 0.0005, 0.0005, 0.0005;
    if (k == 10) b.odom_sigma.head<3>().setConstant(0.5);
    ASSERT_TRUE(opt.addBundle(b).accepted);
  }
  EXPECT_EQ(opt.numLandmarks(false), 1);
}

// KITTI 05 under realistic observations: a peer merged last through a sound transform was
// undone because another peer's estimate had left that peer's own odometry envelope. The
// guard undoes the merge of the robot that left its envelope; the other peer stays merged.
TEST(BackendOptimizer, TheGuardUndoesTheMergeOfThePeerThatLeftItsEnvelopeNotTheNewest) {
  graph_scenario::GraphScenario s = twoRobotIndoor(true);
  // Robot 1's odometry overstates every step by a fifth (a wheel radius set wrong): the
  // landmarks it shares with the host pull its estimate away from what its odometry says.
  scaleOdometry(s.robots[1].bundles, 1.2);
  // Floors the host and robot 2 stay within (their estimates keep within 0.2 m of their
  // odometry) and robot 1 leaves once most of its key poses are in (0.8 m).
  backend::BackendConfig cfg;
  cfg.envelope.gate_sigmas = 0.5;
  cfg.envelope.floor_m = 0.4;
  backend::Optimizer opt(cfg, ClassTable::loadDefault(), 0);
  for (const auto& x : s.robots[0].bundles) ASSERT_TRUE(opt.addBundle(x).accepted);
  const Pose T1 = s.robots[0].truth[0].inverse() * s.robots[1].truth[0];
  const Pose T2 = s.robots[0].truth[0].inverse() * s.robots[2].truth[0];
  // Robot 1 merged first, while its estimate is still near its odometry; robot 2 is the newest
  // merge when robot 1 leaves its envelope.
  for (std::size_t k = 0; k < 10; ++k) ASSERT_TRUE(opt.addBundle(s.robots[1].bundles[k]).accepted);
  ASSERT_TRUE(opt.addRobotTransform(1, T1).accepted);
  ASSERT_TRUE(opt.merged(1));
  for (const auto& x : s.robots[2].bundles) ASSERT_TRUE(opt.addBundle(x).accepted);
  ASSERT_TRUE(opt.addRobotTransform(2, T2).accepted);
  ASSERT_TRUE(opt.merged(2));
  ASSERT_EQ(opt.unmerged(), 0);
  for (std::size_t k = 10; k < s.robots[1].bundles.size(); ++k) ASSERT_TRUE(opt.addBundle(s.robots[1].bundles[k]).accepted);
  opt.fullSolve();
  EXPECT_EQ(opt.unmerged(), 1);
  EXPECT_FALSE(opt.merged(1));
  EXPECT_TRUE(opt.merged(2));
}

// KITTI 05 under realistic observations (seed 6): a peer merged through a sound transform was
// un-merged and merged again through one found at another place of its bent map, 20-45 m off,
// and the host's own trajectory ended 2.8 times its odometry's error. A contradicting
// transform re-merges only when more of the peer's landmarks meet the host's through it than
// meet them now; otherwise it is held back and the estimate stays.
TEST(BackendOptimizer, AContradictingTransformThatExplainsFewerLandmarksIsHeldBack) {
  const graph_scenario::GraphScenario s = twoRobotIndoor();
  backend::Optimizer opt(backend::BackendConfig{}, ClassTable::loadDefault(), 0);
  for (const auto& x : s.robots[0].bundles) ASSERT_TRUE(opt.addBundle(x).accepted);
  const Pose truth = s.robots[0].truth[0].inverse() * s.robots[1].truth[0];
  ASSERT_TRUE(opt.addRobotTransform(1, truth).accepted);
  for (const auto& x : s.robots[1].bundles) ASSERT_TRUE(opt.addBundle(x).accepted);
  opt.fullSolve();
  ASSERT_GE(opt.sharedLandmarks(1), 5);
  const auto before = opt.trajectory(1);
  const backend::UpdateResult r = opt.addRobotTransform(1, poseFromXyzYaw(6.0, -4.0, 0, 0.3) * truth);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("held back"), std::string::npos) << r.reason;
  EXPECT_TRUE(opt.merged(1));
  EXPECT_EQ(opt.unmerged(), 0);
  EXPECT_LT(maxTranslationGap(opt.trajectory(1), before), 0.05);
}

// The mixed indoor team's demo (seed 2): odometry off by -1.2 % and -1.7 % in distance (a
// wheel radius, a visual scale), robots whose odometry the landmarks could only bend step by
// step. With odometry.scale_sigma each robot's scale is a variable of the graph: a robot whose
// odometry reads every step 5 % short ends with a scale near 1 / 0.95 and a trajectory closer
// to the truth than the graph that takes its odometry as it is.
TEST(BackendOptimizer, EstimatesTheOdometryScaleOfARobotWhoseOdometryReadsShort) {
  graph_scenario::GraphScenario s = graph_scenario::makeIndoorScenario(1);
  std::vector<KeyPoseBundle>& bundles = s.robots[0].bundles;
  scaleOdometry(bundles, 0.95);
  auto error = [&](const backend::Optimizer& opt) {
    double sq = 0;
    const auto traj = opt.trajectory(0);
    for (const backend::TrajectoryPose& p : traj)
      sq += (p.pose.translation() - (s.robots[0].truth[0].inverse() * s.robots[0].truth[p.seq]).translation()).squaredNorm();
    return std::sqrt(sq / traj.size());
  };
  backend::BackendConfig with;
  with.odom_scale_sigma = 0.05;
  backend::Optimizer fixed(backend::BackendConfig{}, ClassTable::loadDefault(), 0), estimated(with, ClassTable::loadDefault(), 0);
  for (const KeyPoseBundle& b : bundles) {
    ASSERT_TRUE(fixed.addBundle(b).accepted);
    ASSERT_TRUE(estimated.addBundle(b).accepted);
  }
  fixed.fullSolve();
  estimated.fullSolve();
  EXPECT_DOUBLE_EQ(fixed.odometryScale(0), 1.0);
  EXPECT_NEAR(estimated.odometryScale(0), 1.0 / 0.95, 0.01);
  EXPECT_LT(error(estimated), 0.5 * error(fixed)) << "estimated " << error(estimated) << " m, fixed " << error(fixed) << " m";
}
