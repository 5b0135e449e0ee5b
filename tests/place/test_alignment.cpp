#include <gtest/gtest.h>

#include "place/alignment.h"

using namespace slide;

namespace {
std::vector<Eigen::Vector3d> square() {
  return {{0, 0, 0}, {4, 0, 0.5}, {4, 3, 1}, {0, 3, 0.2}, {2, 1, 2}};
}
}  // namespace

TEST(Alignment, RecoversKnownXyzYawExactly) {
  const Pose T = poseFromXyzYaw(3.0, -2.0, 0.7, 0.9);
  const auto a = square();
  std::vector<Eigen::Vector3d> b;
  for (const auto& p : a) b.push_back(T.inverse() * p);
  const place::Alignment al = place::alignXyzYaw(a, b);
  ASSERT_TRUE(al.ok);
  EXPECT_NEAR((al.T_a_b.matrix() - T.matrix()).norm(), 0, 1e-9);
  EXPECT_NEAR(al.rms, 0, 1e-9);
  ASSERT_EQ(al.residuals.size(), a.size());
}

TEST(Alignment, RobustRefinementIgnoresAGrossOutlier) {
  const Pose T = poseFromXyzYaw(-1.0, 5.0, 0.0, -2.5);
  std::vector<Eigen::Vector3d> a, b;
  for (int i = 0; i < 12; ++i) {
    const Eigen::Vector3d p(std::cos(i) * 7 + i, std::sin(i * 1.3) * 5, 0.1 * i);
    a.push_back(p);
    b.push_back(T.inverse() * p);
  }
  a[3] += Eigen::Vector3d(6, -4, 0);  // a wrong match
  const place::Alignment plain = place::alignXyzYaw(a, b);
  const place::Alignment robust = place::alignXyzYawRobust(a, b, 0.3, 30);
  ASSERT_TRUE(robust.ok);
  EXPECT_GT((plain.T_a_b.translation() - T.translation()).norm(), 0.2);
  EXPECT_LT((robust.T_a_b.translation() - T.translation()).norm(), 0.01);
  EXPECT_GT(robust.residuals[3], 5.0);  // the outlier keeps its large residual
}

TEST(Alignment, DegenerateInputIsNotOk) {
  EXPECT_FALSE(place::alignXyzYaw({}, {}).ok);
  EXPECT_FALSE(place::alignXyzYaw({{1, 2, 3}}, {{1, 2, 3}}).ok);
  EXPECT_FALSE(place::alignXyzYaw({{1, 2, 3}, {4, 5, 6}}, {{1, 1, 0}, {1, 1, 5}}).ok);  // B points stacked
  EXPECT_FALSE(place::alignXyzYaw({{1, 2, 3}, {4, 5, 6}}, {{1, 1, 0}}).ok);
}
