#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "objects/object_map.h"

using namespace slide;

TEST(ObjectMap, QueriesMatchBruteForcePerClass) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-40, 40);
  const int classes[] = {1, 10, 71};
  ObjectMap map;
  for (int i = 0; i < 600; ++i) {
    Object o;
    o.id = i;
    o.class_id = classes[i % 3];
    o.model = Ellipsoid{{u(rng), u(rng), 0.5}, 0.3, 1.0};
    map.add(o);
  }
  for (int q = 0; q < 40; ++q) {
    const Eigen::Vector3d p(u(rng), u(rng), 0);
    const int cls = q % 4 == 3 ? ObjectMap::kAnyClass : classes[q % 3];
    std::vector<std::size_t> expect;
    std::vector<std::pair<double, std::size_t>> by_dist;
    for (std::size_t i = 0; i < map.size(); ++i) {
      if (cls != ObjectMap::kAnyClass && map[i].class_id != cls) continue;
      const double d = (map[i].position() - p).norm();
      if (d <= 6) expect.push_back(i);
      by_dist.emplace_back(d, i);
    }
    auto got = map.radius(p, 6, cls);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, expect);
    std::sort(by_dist.begin(), by_dist.end());
    const auto knn = map.nearest(p, 5, cls);
    ASSERT_EQ(knn.size(), 5u);
    for (int j = 0; j < 5; ++j) {
      EXPECT_EQ(knn[j].first, by_dist[j].second);
      EXPECT_NEAR(knn[j].second, by_dist[j].first, 1e-12);
    }
  }
}

TEST(ObjectMap, IndexFollowsChanges) {
  ObjectMap map;
  Object o;
  o.model = Ellipsoid{{0, 0, 0}, 0.3, 1.0};
  map.add(o);
  EXPECT_EQ(map.radius({0, 0, 0}, 1).size(), 1u);
  std::get<Ellipsoid>(map[0].model).centroid = {10, 0, 0};
  EXPECT_TRUE(map.radius({0, 0, 0}, 1).empty());
  EXPECT_EQ(map.radius({10, 0, 0}, 1).size(), 1u);
  EXPECT_TRUE(map.radius({0, 0, 0}, 100, 42).empty());  // class not present
  const ObjectMap moved = map.transformed(poseFromXyzYaw(0, 0, 0, M_PI / 2));
  EXPECT_TRUE(moved[0].position().isApprox(Eigen::Vector3d(0, 10, 0), 1e-12));
}
