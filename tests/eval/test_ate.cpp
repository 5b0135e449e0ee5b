#include <gtest/gtest.h>

#include "eval/ate.h"

using namespace slide;

namespace {
std::vector<Pose> square() {
  return {poseFromXyzYaw(0, 0, 0, 0), poseFromXyzYaw(10, 0, 0, 0), poseFromXyzYaw(10, 10, 1, 0),
          poseFromXyzYaw(0, 10, 2, 0)};
}
}  // namespace

TEST(Ate, ZeroForARigidlyMovedCopy) {
  const Pose T = poseFromXyzRpy({5, -3, 2}, 0.1, -0.2, 1.0);
  std::vector<Pose> est;
  for (const Pose& p : square()) est.push_back(T * p);
  for (eval::TrajectoryAlignment a : {eval::TrajectoryAlignment::Se3, eval::TrajectoryAlignment::Sim3}) {
    const eval::AteResult r = eval::absoluteTrajectoryError(est, square(), a);
    EXPECT_NEAR(r.rmse, 0, 1e-9);
    EXPECT_TRUE(r.alignment.T.isApprox(T.inverse(), 1e-9));
  }
  // Yaw-only alignment recovers a yaw + translation exactly...
  std::vector<Pose> est4;
  for (const Pose& p : square()) est4.push_back(poseFromXyzYaw(5, -3, 2, 1.0) * p);
  EXPECT_NEAR(eval::absoluteTrajectoryError(est4, square(), eval::TrajectoryAlignment::Yaw4Dof).rmse, 0, 1e-9);
  // ...and no alignment leaves the full offset.
  EXPECT_GT(eval::absoluteTrajectoryError(est, square(), eval::TrajectoryAlignment::None).rmse, 1.0);
}

TEST(Ate, HandComputedErrors) {
  // Without alignment: errors 0, 3, 4, 0 -> rmse sqrt((9+16)/4) = 2.5.
  std::vector<Pose> est = square();
  est[1].translation().y() += 3;
  est[2].translation().x() += 4;
  const eval::AteResult r = eval::absoluteTrajectoryError(est, square(), eval::TrajectoryAlignment::None);
  EXPECT_NEAR(r.rmse, 2.5, 1e-12);
  EXPECT_NEAR(r.max, 4, 1e-12);
  EXPECT_NEAR(r.mean, 1.75, 1e-12);
}

TEST(Ate, Sim3RecoversScale) {
  std::vector<Pose> est;
  for (Pose p : square()) {
    p.translation() *= 0.5;
    est.push_back(p);
  }
  const eval::AteResult r = eval::absoluteTrajectoryError(est, square(), eval::TrajectoryAlignment::Sim3);
  EXPECT_NEAR(r.alignment.scale, 2.0, 1e-9);
  EXPECT_NEAR(r.rmse, 0, 1e-9);
  EXPECT_GT(eval::absoluteTrajectoryError(est, square(), eval::TrajectoryAlignment::Se3).rmse, 1.0);
}

TEST(TrajectoryAlignment, NamesRoundTrip) {
  for (eval::TrajectoryAlignment a : {eval::TrajectoryAlignment::None, eval::TrajectoryAlignment::Se3,
                                      eval::TrajectoryAlignment::Sim3, eval::TrajectoryAlignment::Yaw4Dof})
    EXPECT_EQ(eval::parseAlignment(eval::alignmentName(a)), a);
  EXPECT_THROW(eval::parseAlignment("se2"), std::invalid_argument);
}

TEST(TrajectoryAlignment, YawOnlyLeavesRollAndPitchErrors) {
  // A copy tilted by 0.2 rad of roll cannot be undone by x, y, z, yaw; SE(3) can.
  const Pose tilt = poseFromXyzRpy({0, 0, 0}, 0.2, 0, 0);
  std::vector<Pose> est;
  for (const Pose& p : square()) est.push_back(tilt * p);
  EXPECT_NEAR(eval::absoluteTrajectoryError(est, square(), eval::TrajectoryAlignment::Se3).rmse, 0, 1e-9);
  EXPECT_GT(eval::absoluteTrajectoryError(est, square(), eval::TrajectoryAlignment::Yaw4Dof).rmse, 0.1);
}
