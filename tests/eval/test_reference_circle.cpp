#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "eval/reference_circle.h"

using namespace slide;

// A bark ring (radius 0.2 m, 3 mm roughness) and, as many as 4 in 10 of the points, a branch
// leaving it: the reference keeps to the ring; an all-points circle would not.
TEST(ReferenceCircle, KeepsToTheRingWhenABranchHoldsMuchOfTheSlice) {
  std::mt19937 rng(7);
  std::normal_distribution<double> rough(0, 0.003);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector2d> pts;
  const Eigen::Vector2d centre(3.0, -1.0);
  for (int i = 0; i < 600; ++i) {
    const double a = 2 * M_PI * u(rng), r = 0.2 + rough(rng);
    pts.push_back(centre + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  for (int i = 0; i < 400; ++i)  // a branch 0.1 m thick leaving the ring to the east
    pts.push_back(centre + Eigen::Vector2d(0.2 + 0.6 * u(rng), -0.05 + 0.1 * u(rng)));
  const auto ref = eval::referenceCircle(pts);
  ASSERT_TRUE(ref);
  EXPECT_NEAR(ref->radius, 0.2, 0.002);
  EXPECT_LT((ref->center - centre).norm(), 0.002);
  EXPECT_GE(ref->inliers, 580);
  EXPECT_LT(ref->inliers, 640);
  EXPECT_FALSE(eval::referenceCircle({{0, 0}, {1, 0}, {2, 0}, {3, 0}}));                  // too few
  EXPECT_FALSE(eval::referenceCircle({{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 0}}));  // no circle
}
