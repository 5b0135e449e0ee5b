#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "geometry/kdtree.h"

using namespace slide;

TEST(KdTree, MatchesBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-50, 50);
  std::vector<Eigen::Vector3d> pts(2000);
  for (auto& p : pts) p = {u(rng), u(rng), u(rng) * 0.1};
  const KdTree<3> tree(pts);
  for (int q = 0; q < 50; ++q) {
    const Eigen::Vector3d c(u(rng), u(rng), 0);
    const double r = 3 + q % 7;
    std::vector<std::size_t> expect;
    for (std::size_t i = 0; i < pts.size(); ++i)
      if ((pts[i] - c).norm() <= r) expect.push_back(i);
    auto got = tree.radius(c, r);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, expect);

    const std::size_t k = 1 + q % 9;
    std::vector<std::pair<double, std::size_t>> all;
    for (std::size_t i = 0; i < pts.size(); ++i) all.emplace_back((pts[i] - c).squaredNorm(), i);
    std::sort(all.begin(), all.end());
    const auto knn = tree.nearest(c, k);
    ASSERT_EQ(knn.size(), k);
    for (std::size_t j = 0; j < k; ++j) {
      EXPECT_EQ(knn[j].first, all[j].second);
      EXPECT_DOUBLE_EQ(knn[j].second, all[j].first);
    }
  }
}

TEST(KdTree, EmptyAndDuplicates) {
  const KdTree<2> empty(std::vector<Eigen::Vector2d>{});
  EXPECT_TRUE(empty.radius({0, 0}, 10).empty());
  EXPECT_TRUE(empty.nearest({0, 0}, 3).empty());
  const KdTree<2> dup(std::vector<Eigen::Vector2d>(5, Eigen::Vector2d(1, 1)));
  EXPECT_EQ(dup.radius({1, 1}, 0).size(), 5u);
  EXPECT_EQ(dup.nearest({0, 0}, 10).size(), 5u);
}
