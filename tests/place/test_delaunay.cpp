#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "place/delaunay.h"
#include "place/simplex_descriptor.h"

using namespace slide;

TEST(Delaunay, SquareWithCentreGivesFourTriangles) {
  const std::vector<Eigen::Vector2d> p = {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {2, 2.1}};
  const auto tris = place::delaunay2d(p);
  ASSERT_EQ(tris.size(), 4u);
  for (const place::Triangle& t : tris) EXPECT_TRUE(std::count(t.begin(), t.end(), 4u) == 1);
}

TEST(Delaunay, CollinearDuplicateAndNanInputs) {
  EXPECT_TRUE(place::delaunay2d({{0, 0}, {1, 1}, {2, 2}, {3, 3}, {5, 5}}).empty());
  EXPECT_TRUE(place::delaunay2d({{1, 1}, {1, 1}, {1, 1}}).empty());
  EXPECT_TRUE(place::delaunay2d({}).empty());
  // A duplicate is merged into its first copy; a NaN point is skipped.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto tris = place::delaunay2d({{0, 0}, {3, 0}, {0, 3}, {3, 0.0001}, {nan, 1}});
  ASSERT_EQ(tris.size(), 1u);
  const std::set<std::uint32_t> v(tris[0].begin(), tris[0].end());
  EXPECT_EQ(v, (std::set<std::uint32_t>{0, 1, 2}));
}

TEST(SimplexDescriptor, SortedDistancesWithVerticesInTheSameOrder) {
  std::vector<place::Landmark> lms(3);
  lms[0].p = {0, 0, 0};
  lms[1].p = {6, 0, 0};
  lms[2].p = {0, 3, 0};
  lms[0].class_id = 1;
  lms[1].class_id = 2;
  lms[2].class_id = 3;
  const auto d = place::describeTriangles(lms, {place::Triangle{1, 2, 0}});
  ASSERT_EQ(d.size(), 1u);
  // Centroid (2, 1): distances sqrt(5) (v0), sqrt(17) (v1), sqrt(8) (v2).
  EXPECT_NEAR(d[0].distances[0], std::sqrt(5.0), 1e-12);
  EXPECT_NEAR(d[0].distances[1], std::sqrt(8.0), 1e-12);
  EXPECT_NEAR(d[0].distances[2], std::sqrt(17.0), 1e-12);
  EXPECT_EQ(d[0].vertices, (place::Triangle{0, 2, 1}));
  EXPECT_EQ(d[0].classes, (std::array<int, 3>{1, 3, 2}));
}
