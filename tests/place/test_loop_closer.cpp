#include <gtest/gtest.h>

#include <optional>
#include <random>

#include "eval/transform_error.h"
#include "place/loop_closer.h"
#include "place/map_perturb.h"
#include "io/object_map_text.h"
#include "objects/class_table.h"

using namespace slide;

namespace {
// Mixed-class objects over a w x w square with ids starting at `first_id`.
ObjectMap sceneMap(int n, double w, unsigned seed, std::int64_t first_id) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, w);
  const int classes[] = {71, 1, 2, 0};
  ObjectMap m;
  for (int i = 0; i < n; ++i) {
    Object o;
    o.id = first_id + i;
    o.class_id = classes[i % 4];
    o.model = Ellipsoid{{u(rng), u(rng), 0.5}, 0.3, 1.0};
    m.add(o);
  }
  return m;
}

ObjectMap movedCopy(const ObjectMap& m, const Pose& T_a_b, std::int64_t id_offset, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, 0.03);
  ObjectMap out;
  for (const Object& o : m.objects()) {
    Object c = transformObject(T_a_b.inverse(), o);
    std::get<Ellipsoid>(c.model).centroid += Eigen::Vector3d(n(rng), n(rng), 0);
    c.id = o.id + id_offset;
    out.add(c);
  }
  return out;
}
}  // namespace

TEST(LoopCloser, InterRobotCheckIsStaggeredRepeatedOnChangeAndRefined) {
  place::LoopCloserParams p;
  p.robot = 0;
  p.inter_period_s = 5;
  p.stagger_s = 1;
  place::LoopCloser lc(p);
  const ObjectMap own = sceneMap(80, 40, 1, 0);
  const Pose truth = poseFromXyzYaw(12, -7, 0.3, 1.2);
  lc.setOwnMap(own, 0.0);
  lc.setPeerMap(2, movedCopy(own, truth, 1000, 2), 0.0);
  EXPECT_TRUE(lc.poll(0.0).empty());  // robot 0, peer 2: first check staggered to t = 2 s
  auto out = lc.poll(2.0);
  ASSERT_EQ(out.size(), 1u) << lc.lastReason();
  EXPECT_EQ(out[0].outcome, place::ConsensusFilter::Outcome::Accepted);
  EXPECT_EQ(out[0].robot_a, 0);
  EXPECT_EQ(out[0].robot_b, 2);
  EXPECT_LT(eval::transformError(out[0].T_a_b, truth).translation_m, 0.05);
  for (const auto& [ida, idb] : out[0].inliers) EXPECT_EQ(idb, ida + 1000);
  EXPECT_TRUE(lc.poll(8.0).empty());  // nothing changed: no re-check
  lc.setPeerMap(2, movedCopy(own, truth, 1000, 3), 8.0);
  out = lc.poll(9.0);  // changed and due (the period ran out at t = 7 s)
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].outcome, place::ConsensusFilter::Outcome::Refined);
}

TEST(LoopCloser, UnrelatedPeerGivesNoClosureAndAReason) {
  place::LoopCloser lc(place::LoopCloserParams{});
  lc.setOwnMap(sceneMap(80, 40, 1, 0), 0);
  lc.setPeerMap(1, sceneMap(80, 40, 9, 500), 0);
  lc.setPeerMap(3, sceneMap(3, 40, 9, 900), 0);
  for (double t = 0; t < 20; t += 1) EXPECT_TRUE(lc.poll(t).empty());
  EXPECT_FALSE(lc.lastReason().empty());
}

TEST(LoopCloser, IntraRobotMatchesRecentDuplicatesAgainstOldObjects) {
  place::LoopCloserParams p;
  p.intra_min_keypose_gap = 30;
  p.intra_trigger_radius_m = 5;
  p.intra_local_radius_m = 40;
  place::LoopCloser lc(p);
  // The robot starts at (20, 20), maps the objects around it, drives away and comes back.
  std::vector<place::KeyPose> traj;
  for (int k = 0; k <= 10; ++k) traj.push_back({k, poseFromXyzYaw(20 + 0.1 * k, 20, 0, 0)});
  lc.setTrajectory(traj);
  const ObjectMap old = sceneMap(60, 40, 4, 0);
  lc.setOwnMap(old, 1.0);
  for (int k = 11; k <= 60; ++k) traj.push_back({k, poseFromXyzYaw(20 + 30 * std::sin(k * 0.126), 20, 0, 0)});
  traj.push_back({61, poseFromXyzYaw(21, 20, 0, 0)});
  lc.setTrajectory(traj);
  // Drift: on return the tracker re-created the objects 0.8 m and 3 degrees off, with new ids.
  const Pose drift = poseFromXyzYaw(0.8, -0.4, 0, 0.05);
  ObjectMap both = old;
  const ObjectMap duplicates = movedCopy(old, drift, 5000, 5);
  for (const Object& o : duplicates.objects()) both.add(o);
  lc.setOwnMap(both, 2.0);
  const auto out = lc.poll(3.0);
  ASSERT_EQ(out.size(), 1u) << lc.lastReason();
  EXPECT_EQ(out[0].robot_a, out[0].robot_b);
  EXPECT_EQ(out[0].keypose_b, 61);
  EXPECT_LE(out[0].keypose_a, 61 - 30);
  EXPECT_LT(eval::transformError(out[0].result.T_a_b, drift).translation_m, 0.05);  // the match, in the robot's frame
  for (const auto& [ida, idb] : out[0].inliers) EXPECT_EQ(idb, ida + 5000);
}

// The intra-robot closure is what the optimizer takes: the pose of key pose b's body in key
// pose a's body — not the match of the recent objects onto the old ones in the robot's frame,
// which differs from it by the key poses' placement (here: back at the start the other way
// round, 400 m from the origin: a drift of 4.6 degrees about the place is a match that moves
// the robot's origin by 34 m).
TEST(LoopCloser, IntraRobotClosureIsTheBodyPoseOfKeyPoseBInKeyPoseA) {
  place::LoopCloserParams p;
  p.intra_min_keypose_gap = 30;
  p.intra_trigger_radius_m = 5;
  p.intra_local_radius_m = 40;
  p.consensus.initial_confirmations = 1;
  place::LoopCloser lc(p);
  const Pose origin = poseFromXyzYaw(400, 0, 0, 0);  // the place, in the robot's frame
  const ObjectMap scene = sceneMap(60, 40, 4, 0);
  ObjectMap old;
  for (const Object& o : scene.objects()) old.add(transformObject(origin, o));
  const Pose truth_a = origin * poseFromXyzYaw(20, 20, 0, 0.3);
  const Pose truth_b = origin * poseFromXyzYaw(21, 20.5, 0, 0.3 + M_PI);
  // Odometry drifted by `drift` between the two visits: the robot places itself and the objects
  // it sees again (duplicates, new ids) by drift^-1.
  const Pose centre = origin * poseFromXyzYaw(22, 21, 0, 0);
  const Pose drift = poseFromXyzYaw(0.5, -0.3, 0, 0) * centre * poseFromXyzYaw(0, 0, 0, 0.08) * centre.inverse();
  std::vector<place::KeyPose> traj;
  for (int k = 0; k <= 10; ++k) traj.push_back({k, truth_a});
  lc.setTrajectory(traj);
  lc.setOwnMap(old, 1.0);
  for (int k = 11; k <= 60; ++k) traj.push_back({k, poseFromXyzYaw(600, 600, 0, 0)});
  traj.push_back({61, drift.inverse() * truth_b});
  lc.setTrajectory(traj);
  ObjectMap both = old;
  const ObjectMap duplicates = movedCopy(old, drift, 5000, 5);
  for (const Object& o : duplicates.objects()) both.add(o);
  lc.setOwnMap(both, 2.0);
  auto out = lc.poll(3.0);
  ASSERT_EQ(out.size(), 1u) << lc.lastReason();
  EXPECT_EQ(out[0].outcome, place::ConsensusFilter::Outcome::Accepted);
  const Pose truth_ab = truth_a.inverse() * truth_b;
  EXPECT_EQ(out[0].keypose_a, 10);
  EXPECT_EQ(out[0].keypose_b, 61);
  eval::TransformError e = eval::transformError(out[0].T_a_b, truth_ab);
  EXPECT_LT(e.translation_m, 0.1);
  EXPECT_LT(e.rotation_deg, 0.5);

  // The optimizer took it in: key pose 61 and the recent objects moved back by drift. A
  // re-check of the place measures that correction, not the place: one that agrees re-sends the
  // closure given, unchanged.
  traj.back().pose = truth_b;
  traj.push_back({62, truth_b});
  lc.setTrajectory(traj);
  both = old;
  const ObjectMap corrected = movedCopy(old, Pose::Identity(), 5000, 6);
  for (const Object& o : corrected.objects()) both.add(o);
  lc.setOwnMap(both, 4.0);
  const Pose given = out[0].T_a_b;
  out = lc.poll(6.0);
  ASSERT_EQ(out.size(), 1u) << lc.lastReason();
  EXPECT_EQ(out[0].outcome, place::ConsensusFilter::Outcome::Refined);
  EXPECT_EQ(out[0].keypose_a, 10);
  EXPECT_EQ(out[0].keypose_b, 61);
  EXPECT_TRUE(out[0].T_a_b.isApprox(given));
}

// Back at an old place after a long way, the own estimate may be further off than the trigger
// radius: the radii grow by drift_fraction of the path driven in between.
TEST(LoopCloser, IntraRobotTriggerAllowsForDriftAlongThePath) {
  const ObjectMap old = sceneMap(60, 40, 4, 0);
  const Pose drift = poseFromXyzYaw(12, 0, 0, 0);  // 12 m off after 300 m
  ObjectMap both = old;
  const ObjectMap duplicates = movedCopy(old, drift, 5000, 5);
  for (const Object& o : duplicates.objects()) both.add(o);
  for (const double fraction : {0.0, 0.02}) {
    place::LoopCloserParams p;
    p.intra_trigger_radius_m = 10;
    p.intra_local_radius_m = 25;
    p.intra_drift_fraction = fraction;
    p.consensus.initial_confirmations = 1;
    place::LoopCloser lc(p);
    std::vector<place::KeyPose> traj;
    for (int k = 0; k <= 10; ++k) traj.push_back({k, poseFromXyzYaw(20, 20, 0, 0)});
    lc.setTrajectory(traj);
    lc.setOwnMap(old, 1.0);
    for (int k = 11; k <= 60; ++k) traj.push_back({k, poseFromXyzYaw(k % 2 ? 320 : 20, 20, 0, 0)});  // 300 m legs
    traj.push_back({61, drift.inverse() * poseFromXyzYaw(20, 20, 0, 0)});
    lc.setTrajectory(traj);
    lc.setOwnMap(both, 2.0);
    const auto out = lc.poll(3.0);
    if (fraction == 0.0) {
      EXPECT_TRUE(out.empty());
      EXPECT_NE(lc.lastReason().find("no key pose"), std::string::npos) << lc.lastReason();
    } else {
      ASSERT_EQ(out.size(), 1u) << lc.lastReason();
      EXPECT_LT(eval::transformError(out[0].result.T_a_b, drift).translation_m, 0.05);
    }
  }
}

// A 200,000-object map: SlideGraph stops on its time budget (no transform, flagged and
// counted); a map update over max_map_objects is dropped and counted, the previous map stays.
TEST(LoopCloser, LargeMapsAreBoundedByTheTimeBudgetAndTheMapSizeLimit) {
  place::LoopCloserParams p;
  p.robot = 0;
  p.stagger_s = 0;
  p.place.slidegraph.budget_ms = 20;
  p.max_map_objects = 300000;
  place::LoopCloser lc(p);
  const ObjectMap big = sceneMap(200000, 4000, 5, 0);
  ASSERT_TRUE(lc.setOwnMap(big, 0.0));
  ASSERT_TRUE(lc.setPeerMap(1, movedCopy(big, poseFromXyzYaw(5, 3, 0, 0.4), 1000000, 6), 0.0));
  EXPECT_TRUE(lc.poll(0.0).empty());
  EXPECT_EQ(lc.counts().budget_exceeded, 1);
  EXPECT_NE(lc.lastReason().find("time budget of 20 ms exceeded"), std::string::npos) << lc.lastReason();

  const std::vector<place::Landmark> a = place::landmarksOf(big);
  const place::PlaceResult r = place::slideGraph(a, a, p.place.slidegraph);
  EXPECT_FALSE(r.found);
  EXPECT_TRUE(r.budget_exhausted);
  EXPECT_TRUE(r.inliers.empty());

  place::LoopCloserParams q = p;
  q.max_map_objects = 1000;
  place::LoopCloser small(q);
  const ObjectMap own = sceneMap(80, 40, 1, 0);
  ASSERT_TRUE(small.setOwnMap(own, 0.0));
  EXPECT_FALSE(small.setPeerMap(2, sceneMap(1001, 400, 2, 5000), 0.0));
  EXPECT_FALSE(small.setOwnMap(sceneMap(1001, 400, 3, 0), 0.0));
  EXPECT_EQ(small.counts().oversized_maps, 2);
  ASSERT_TRUE(small.setPeerMap(2, movedCopy(own, poseFromXyzYaw(1, 2, 0, 0.3), 1000, 2), 0.0));
  EXPECT_EQ(small.poll(10.0).size(), 1u) << small.lastReason();  // the kept 80-object own map still matches
  EXPECT_EQ(small.counts().budget_exceeded, 0);
}

namespace {
ObjectMap recordedObjects(const std::string& path) {
  const std::string file = std::string(SLIDE_SOURCE_DIR) + "/tests/data/recorded/" + path;
  return io::readObjectMapText(file, ClassTable::loadDefault(), io::MissingSize::Zero).map;
}

// A robot's loop closer fed recorded pairs of its own map and one peer's, a check 5 s apart,
// with config/loop_closer.yaml's consensus; `held` is the last transform it published.
struct RecordedChecks {
  RecordedChecks(int robot, int peer, const place::ConsensusParams& consensus)
      : peer(peer), lc([&] {
          place::LoopCloserParams p;
          p.robot = robot;
          p.consensus = consensus;
          return p;
        }()) {}
  void check(const ObjectMap& own, const ObjectMap& peer_map) {
    lc.setOwnMap(own, t);
    lc.setPeerMap(peer, peer_map, t);
    for (const place::LoopClosure& c : lc.poll(t += 5.0))
      if (c.robot_b == peer && c.outcome != place::ConsensusFilter::Outcome::Pending) held = c.T_a_b;
  }
  int peer;
  place::LoopCloser lc;
  std::optional<Pose> held;
  double t = 0;
};
}  // namespace

// tests/data/recorded/urban_half_turn_alias_held/README.md: robot 0 held robot 1 through a half
// turn of the block grid found in two checks of the small early maps; every later check of the grown
// maps found the true alignment stronger but the alias nearly as strong (ambiguous: no result),
// so the alias stayed to the end of the run. With ambiguous_may_replace the later checks' true
// alignment replaces it.
TEST(LoopCloser, AHalfTurnAliasHeldFromSmallMapsIsReplacedWhenLaterChecksFindTheTruthStronger) {
  auto map = [](const std::string& name) { return recordedObjects("urban_half_turn_alias_held/" + name + ".txt"); };
  const Pose truth = poseFromXyzYaw(-55.872, -68.475, 0.0, M_PI / 2);  // the simulator's start poses
  for (const bool may_replace : {true, false}) {
    place::ConsensusParams consensus{1.0, 3.0, 2, 3, 10};  // config/loop_closer.yaml
    consensus.ambiguous_may_replace = may_replace;
    RecordedChecks run(0, 1, consensus);
    run.check(map("own_1"), map("peer_1"));
    run.check(map("own_2"), map("peer_2"));
    ASSERT_TRUE(run.held) << run.lc.lastReason();
    EXPECT_GT(eval::transformError(*run.held, truth).translation_m, 50.0) << "the early maps' answer is the alias";
    for (int k = 0; k < 5; ++k) run.check(map("own_late"), map("peer_late"));
    const eval::TransformError e = eval::transformError(*run.held, truth);
    if (may_replace) {
      EXPECT_LT(e.translation_m, 1.0);
      EXPECT_LT(e.yaw_deg, 2.0);
    } else {
      EXPECT_GT(e.translation_m, 50.0) << "without it the alias stays";
    }
  }
}

// tests/data/recorded/urban_pending_confirmed_by_ambiguous/README.md: robot 1 found robot 0
// once, unambiguously (83 inliers, pending: two agreeing results make the first transform), then
// every check of the grown maps was ambiguous on the same alignment when each match counted 1
// (ambiguous_may_confirm was added to confirm it; test_consensus.cpp checks that rule). Weighed
// by their fit, the later checks find the truth clearly (strength ratio 4.61) and confirm the
// pending alignment with neither rescue.
TEST(LoopCloser, APendingAlignmentIsConfirmedByLaterChecksThatFindItClearly) {
  auto map = [](const std::string& name) {
    return recordedObjects("urban_pending_confirmed_by_ambiguous/" + name + ".txt");
  };
  place::ConsensusParams consensus{1.0, 3.0, 2, 3, 10};  // config/loop_closer.yaml
  consensus.ambiguous_may_confirm = false;
  consensus.ambiguous_may_replace = false;
  RecordedChecks run(1, 0, consensus);
  run.check(map("own_found"), map("peer_found"));
  EXPECT_FALSE(run.held);
  run.check(map("own_late"), map("peer_late"));
  EXPECT_EQ(run.lc.lastReason().find("ambiguous"), std::string::npos) << run.lc.lastReason();
  ASSERT_TRUE(run.held) << run.lc.lastReason();
  const eval::TransformError e = eval::transformError(*run.held, poseFromXyzYaw(68.475, -55.872, 0.0, -M_PI / 2));
  EXPECT_LT(e.translation_m, 1.0);
  EXPECT_LT(e.yaw_deg, 2.0);
}
