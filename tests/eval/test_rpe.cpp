#include <gtest/gtest.h>

#include <cmath>

#include "eval/rpe.h"
#include "eval/time_association.h"
#include "eval/transform_error.h"

using namespace slide;

namespace {
// Straight line along x, one metre per frame.
std::vector<Pose> line(int n) {
  std::vector<Pose> out;
  for (int i = 0; i < n; ++i) out.push_back(poseFromXyzYaw(i, 0, 0, 0));
  return out;
}
}  // namespace

TEST(Rpe, HandComputedTranslationErrors) {
  // Estimate steps: 1, 1.5, 1, 1 (frame 2 onwards shifted by 0.5 in x).
  std::vector<Pose> est = line(5);
  for (int i = 2; i < 5; ++i) est[i].translation().x() += 0.5;
  const eval::RpeResult r = eval::relativePoseError(est, line(5), {1.0, eval::DeltaUnit::Frames});
  ASSERT_EQ(r.trans_errors.size(), 4u);
  EXPECT_NEAR(r.trans_errors[0], 0, 1e-12);
  EXPECT_NEAR(r.trans_errors[1], 0.5, 1e-12);
  EXPECT_NEAR(r.translation.rmse, std::sqrt(0.25 / 4), 1e-12);
  EXPECT_NEAR(r.translation.max, 0.5, 1e-12);
  EXPECT_NEAR(r.rotation_deg.max, 0, 1e-9);
  // Delta 2 frames: pairs (0,2) (1,3) (2,4); the jump falls inside the first two.
  const eval::RpeResult r2 = eval::relativePoseError(est, line(5), {2.0, eval::DeltaUnit::Frames});
  ASSERT_EQ(r2.trans_errors.size(), 3u);
  EXPECT_NEAR(r2.trans_errors[0], 0.5, 1e-12);
  EXPECT_NEAR(r2.trans_errors[1], 0.5, 1e-12);
  EXPECT_NEAR(r2.trans_errors[2], 0.0, 1e-12);
}

TEST(Rpe, RotationErrorOfAYawDrift) {
  // The estimate turns 10 degrees at frame 1 and back at frame 2: each one-frame step has a
  // 10 deg rotation error and no translation error; over two frames the rotations cancel and
  // the end point is off by |(1,0) - R(10deg)(1,0)| = 2 sin(5 deg).
  std::vector<Pose> ref = line(3), est = line(3);
  const double a = 10 * M_PI / 180;
  est[1] = poseFromXyzYaw(1, 0, 0, a);
  est[2] = est[1] * poseFromXyzYaw(1, 0, 0, -a);
  const eval::RpeResult r = eval::relativePoseError(est, ref, {1.0, eval::DeltaUnit::Frames});
  ASSERT_EQ(r.rot_errors_deg.size(), 2u);
  EXPECT_NEAR(r.rot_errors_deg[0], 10, 1e-9);
  EXPECT_NEAR(r.rot_errors_deg[1], 10, 1e-9);
  EXPECT_NEAR(r.translation.max, 0, 1e-12);
  const eval::RpeResult r2 = eval::relativePoseError(est, ref, {2.0, eval::DeltaUnit::Frames});
  ASSERT_EQ(r2.trans_errors.size(), 1u);
  EXPECT_NEAR(r2.trans_errors[0], 2 * std::sin(a / 2), 1e-12);
  EXPECT_NEAR(r2.rot_errors_deg[0], 0, 1e-6);
}

TEST(Rpe, DeltaInMetresAndRigidInvariance) {
  // Frames every 0.5 m: a 2 m delta pairs i with i + 4.
  std::vector<Pose> ref;
  for (int i = 0; i < 9; ++i) ref.push_back(poseFromXyzYaw(0.5 * i, 0, 0, 0));
  const eval::RpeResult r = eval::relativePoseError(ref, ref, {2.0, eval::DeltaUnit::Metres});
  ASSERT_EQ(r.first.size(), 5u);
  EXPECT_EQ(r.second[0], 4u);
  EXPECT_NEAR(r.translation.max, 0, 1e-12);
  // A rigidly moved copy has no relative error; a half-scale copy does unless rescaled.
  const Pose T = poseFromXyzRpy({3, 1, 2}, 0.2, 0.1, 1.2);
  std::vector<Pose> moved, half;
  for (const Pose& p : ref) {
    moved.push_back(T * p);
    Pose h = p;
    h.translation() *= 0.5;
    half.push_back(h);
  }
  EXPECT_NEAR(eval::relativePoseError(moved, ref, {1, eval::DeltaUnit::Frames}).translation.max, 0, 1e-9);
  EXPECT_NEAR(eval::relativePoseError(half, ref, {1, eval::DeltaUnit::Frames}).translation.max, 0.25, 1e-12);
  EXPECT_NEAR(eval::relativePoseError(half, ref, {1, eval::DeltaUnit::Frames, 2.0}).translation.max, 0, 1e-12);
  EXPECT_NEAR(eval::pathLength(ref), 4.0, 1e-12);
}

TEST(Rpe, RejectsBadInput) {
  EXPECT_THROW(eval::relativePoseError(line(3), line(4)), std::invalid_argument);
  EXPECT_THROW(eval::relativePoseError(line(3), line(3), {0.5, eval::DeltaUnit::Frames}), std::invalid_argument);
  EXPECT_THROW(eval::relativePoseError(line(3), line(3), {0.0, eval::DeltaUnit::Metres}), std::invalid_argument);
  EXPECT_TRUE(eval::relativePoseError(line(3), line(3), {5, eval::DeltaUnit::Frames}).trans_errors.empty());
}

TEST(TimeAssociation, NearestWithinMaxDifferenceOneToOne) {
  const std::vector<double> est{0.0, 0.98, 1.04, 2.5, 3.0};
  const std::vector<double> ref{3.01, 0.01, 1.0, 2.0};  // unsorted on purpose
  const auto pairs = eval::associateByTime(est, ref, 0.05);
  // 0.0-0.01, 1.04 loses ref 1.0 to 0.98, 2.5 too far, 3.0-3.01.
  ASSERT_EQ(pairs.size(), 3u);
  EXPECT_EQ(pairs[0], std::make_pair(std::size_t(0), std::size_t(1)));
  EXPECT_EQ(pairs[1], std::make_pair(std::size_t(1), std::size_t(2)));
  EXPECT_EQ(pairs[2], std::make_pair(std::size_t(4), std::size_t(0)));
  // With an offset of +1 s: 1.0-1.0, 1.98-2.0 (2.04 loses 2.0), 3.5 and 4.0 find nothing.
  const auto shifted = eval::associateByTime(est, ref, 0.05, 1.0);
  ASSERT_EQ(shifted.size(), 2u);
  EXPECT_EQ(shifted[0], std::make_pair(std::size_t(0), std::size_t(2)));
  EXPECT_EQ(shifted[1], std::make_pair(std::size_t(1), std::size_t(3)));
}

TEST(TimeAssociation, PosesAndErrorWhenNothingMatches) {
  std::vector<StampedPose> a{{0.0, poseFromXyzYaw(1, 0, 0, 0)}, {1.0, poseFromXyzYaw(2, 0, 0, 0)}};
  std::vector<StampedPose> b{{0.001, poseFromXyzYaw(5, 0, 0, 0)}, {1.002, poseFromXyzYaw(6, 0, 0, 0)}};
  const eval::AssociatedPoses p = eval::associatePoses(a, b, 0.01);
  ASSERT_EQ(p.t.size(), 2u);
  EXPECT_DOUBLE_EQ(p.t[1], 1.002);
  EXPECT_DOUBLE_EQ(p.ref[1].translation().x(), 6);
  b[0].t = 100;
  b[1].t = 101;
  try {
    eval::associatePoses(a, b, 0.01);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("[100, 101]"), std::string::npos) << e.what();
  }
}

TEST(TransformError, HandComputed) {
  const Pose truth = poseFromXyzYaw(1, 2, 0, 0.1);
  const Pose est = poseFromXyzYaw(4, 6, 0, 0.1 + 5 * M_PI / 180);
  const eval::TransformError e = eval::transformError(est, truth);
  EXPECT_NEAR(e.translation_m, 5, 1e-12);
  EXPECT_NEAR(e.yaw_deg, 5, 1e-9);
  EXPECT_NEAR(e.rotation_deg, 5, 1e-9);
  // Yaw error wraps: 179 deg vs -179 deg is 2 deg apart.
  const eval::TransformError w =
      eval::transformError(poseFromXyzYaw(0, 0, 0, M_PI * 179 / 180), poseFromXyzYaw(0, 0, 0, -M_PI * 179 / 180));
  EXPECT_NEAR(w.yaw_deg, 2, 1e-9);
  // A roll error shows in the rotation angle, not in yaw.
  const eval::TransformError r = eval::transformError(poseFromXyzRpy({0, 0, 0}, 0.1, 0, 0), Pose::Identity());
  EXPECT_NEAR(r.yaw_deg, 0, 1e-9);
  EXPECT_NEAR(r.rotation_deg, 0.1 * 180 / M_PI, 1e-9);
}

TEST(Rpe, SmallRotationsAreAccurate) {
  // 1 microradian: acos of the trace would lose it in rounding; the result must be exact.
  std::vector<Pose> ref = line(2), est = line(2);
  est[1] = poseFromXyzYaw(1, 0, 0, 1e-6);
  const eval::RpeResult r = eval::relativePoseError(est, ref);
  EXPECT_NEAR(r.rot_errors_deg[0], 1e-6 * 180 / M_PI, 1e-12);
  EXPECT_NEAR(eval::transformError(est[1], ref[1]).rotation_deg, 1e-6 * 180 / M_PI, 1e-12);
}
