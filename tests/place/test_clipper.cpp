#include <gtest/gtest.h>

#include <random>

#include "place/clipper.h"
#include "geometry/pose.h"

using namespace slide;

// Four points of A; B sees three of them (point 2 dropped) under a known rotation and shift.
// All 4 x 3 associations are putative; exactly (0,0), (1,1), (3,2) are right.
TEST(Clipper, FourPointsUnderRotationWithADroppedPoint) {
  const std::vector<Eigen::Vector3d> pa = {{0, 0, 0}, {5, 0, 0}, {5, 3, 0}, {1, 7, 0}};
  const Pose T_b_a = poseFromXyzYaw(10, -4, 0, 1.1);
  const std::vector<Eigen::Vector3d> pb = {T_b_a * pa[0], T_b_a * pa[1], T_b_a * pa[3]};
  std::vector<place::Association> assoc;
  for (std::uint32_t i = 0; i < 4; ++i)
    for (std::uint32_t j = 0; j < 3; ++j) assoc.push_back({i, j});
  const place::ClipperResult r = place::clipper(pa, pb, assoc, place::ClipperParams{});
  std::vector<std::pair<std::uint32_t, std::uint32_t>> got;
  for (std::size_t k : r.selected) got.emplace_back(assoc[k].a, assoc[k].b);
  const std::vector<std::pair<std::uint32_t, std::uint32_t>> expect = {{0, 0}, {1, 1}, {3, 2}};
  EXPECT_EQ(got, expect);
}

TEST(Clipper, GraphHoldsOnlyConsistentDistinctPairs) {
  // Distances in A: |0-1| = 5, |0-2| = 5.83..., |1-2| = 3. B: a copy.
  const std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {5, 0, 0}, {5, 3, 0}};
  const std::vector<place::Association> assoc = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 0}};
  const place::ConsistencyGraph g(p, p, assoc, place::ConsistencyParams{0.1, 0.2});
  // Consistent: (0,0)-(1,1), (0,0)-(2,2), (1,1)-(2,2), (0,1)-(1,0) [|a0-a1| = |b1-b0|].
  // (0,1)-(2,2): |a0-a2| = 5.83 vs |b1-b2| = 3; pairs sharing a landmark never count.
  EXPECT_EQ(g.numEdges(), 4u);
  EXPECT_TRUE(g.consistent(0, 1));
  EXPECT_TRUE(g.consistent(2, 1));
  EXPECT_TRUE(g.consistent(3, 4));
  EXPECT_FALSE(g.consistent(0, 3));  // share A landmark 0
  EXPECT_FALSE(g.consistent(3, 2));
  EXPECT_NEAR(*g.weightsBegin(3), 1.0, 1e-6);
}

TEST(Clipper, FindsTheInlierSetAmongManyOutliersDeterministically) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-30, 30);
  std::normal_distribution<double> n(0, 0.03);
  std::vector<Eigen::Vector3d> pa, pb;
  for (int i = 0; i < 60; ++i) pa.emplace_back(u(rng), u(rng), 0);
  const Pose T_b_a = poseFromXyzYaw(3, 4, 0, -0.4);
  for (const auto& p : pa) pb.push_back(T_b_a * p + Eigen::Vector3d(n(rng), n(rng), 0));
  std::vector<place::Association> assoc;
  for (std::uint32_t i = 0; i < 25; ++i) assoc.push_back({i, i});  // 25 right
  std::uniform_int_distribution<std::uint32_t> pick(0, 59);
  for (int k = 0; k < 400; ++k) {  // 400 random, almost all wrong
    const std::uint32_t i = pick(rng), j = pick(rng);
    if (i != j) assoc.push_back({i, j});
  }
  const place::ClipperResult r1 = place::clipper(pa, pb, assoc, place::ClipperParams{});
  const place::ClipperResult r2 = place::clipper(pa, pb, assoc, place::ClipperParams{});
  EXPECT_EQ(r1.selected, r2.selected);
  int right = 0;
  for (std::size_t k : r1.selected) right += assoc[k].a == assoc[k].b;
  EXPECT_EQ(right, 25);
  EXPECT_EQ(r1.selected.size(), 25u);
  EXPECT_GT(r1.peak_bytes, 0u);
}

TEST(Clipper, EmptyAndSingleAssociation) {
  const std::vector<Eigen::Vector3d> p = {{0, 0, 0}};
  EXPECT_TRUE(place::clipper(p, p, {}, place::ClipperParams{}).selected.empty());
  const place::ClipperResult r = place::clipper(p, p, {{0, 0}}, place::ClipperParams{});
  ASSERT_EQ(r.selected.size(), 1u);
}
