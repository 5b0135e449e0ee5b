#include <gtest/gtest.h>

#include "geometry/pose.h"

using namespace slide;

TEST(Pose, WrapAngle) {
  EXPECT_NEAR(wrapAngle(3 * M_PI / 2), -M_PI / 2, 1e-12);
  EXPECT_NEAR(wrapAngle(-3 * M_PI / 2), M_PI / 2, 1e-12);
  EXPECT_NEAR(wrapAngle(M_PI), M_PI, 1e-12);
  EXPECT_NEAR(wrapAngle(-M_PI), M_PI, 1e-12);
  EXPECT_NEAR(wrapAngle(0.3 + 4 * M_PI), 0.3, 1e-12);
}

TEST(Pose, XyzYawRoundTrip) {
  const Pose T = poseFromXyzYaw(1, -2, 3, 2.5);
  const Eigen::Vector4d v = xyzYawOf(T);
  EXPECT_NEAR(v[0], 1, 1e-12);
  EXPECT_NEAR(v[1], -2, 1e-12);
  EXPECT_NEAR(v[2], 3, 1e-12);
  EXPECT_NEAR(v[3], 2.5, 1e-12);
  // A point one metre ahead of a robot at (1,-2) facing 90 degrees lies at (1,-1).
  const Eigen::Vector3d p = poseFromXyzYaw(1, -2, 0, M_PI / 2) * Eigen::Vector3d(1, 0, 0);
  EXPECT_TRUE(p.isApprox(Eigen::Vector3d(1, -1, 0), 1e-12));
}

TEST(Pose, YawIgnoresRollAndPitch) {
  const Pose T = poseFromXyzRpy({0, 0, 0}, 0.05, -0.03, 1.2);
  EXPECT_NEAR(yawOf(T.linear()), 1.2, 1e-12);
}

TEST(Pose, RpyOfInvertsPoseFromXyzRpy) {
  const Pose T = poseFromXyzRpy({0, 0, 0}, 0.05, -0.03, 1.2);
  EXPECT_TRUE(rpyOf(T.linear()).isApprox(Eigen::Vector3d(0.05, -0.03, 1.2), 1e-12));
  const Pose U = poseFromXyzRpy({0, 0, 0}, -2.9, 1.1, -3.0);
  EXPECT_TRUE(rpyOf(U.linear()).isApprox(Eigen::Vector3d(-2.9, 1.1, -3.0), 1e-12));
}

TEST(Pose, ExpLogInverse) {
  Vector6d xi;
  xi << 0.4, -1.0, 2.0, 0.3, -0.2, 1.1;
  const Pose T = expSE3(xi);
  EXPECT_TRUE(logSE3(T).isApprox(xi, 1e-10));
  // Pure translation: exp is the identity rotation plus the translation.
  Vector6d t;
  t << 1, 2, 3, 0, 0, 0;
  EXPECT_TRUE(expSE3(t).translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  // Rotation by pi/2 about z with translation along the arc: hand-computed.
  Vector6d r;
  r << M_PI / 2, 0, 0, 0, 0, M_PI / 2;  // unit-speed arc of radius 1, quarter turn
  EXPECT_TRUE(expSE3(r).translation().isApprox(Eigen::Vector3d(1, 1, 0), 1e-12));
}
