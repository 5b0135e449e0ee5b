#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "eval/transform_error.h"
#include "place/map_perturb.h"
#include "place/slidegraph.h"
#include "place/slidematch.h"
#include "place/verify.h"

using namespace slide;

namespace {
place::Landmark at(double x, double y, double z, int cls = 71, std::size_t index = 0) {
  place::Landmark l;
  l.p = {x, y, z};
  l.class_id = cls;
  l.size = {0.4, 0.4, 2.0};
  l.index = index;
  return l;
}

place::PlaceResult withInliers(const Pose& T, std::vector<std::pair<std::size_t, std::size_t>> pairs) {
  place::PlaceResult r;
  r.found = true;
  r.T_a_b = T;
  for (const auto& [a, b] : pairs) r.inliers.push_back({a, b});
  r.support = static_cast<double>(pairs.size());  // every match a perfect fit
  return r;
}
}  // namespace

TEST(Verify, MatchesAreGatedHorizontallyAndVerticallyApart) {
  const std::vector<place::Landmark> a{at(0, 0, 0), at(10, 0, 0), at(20, 0, 0)};
  const place::LandmarkIndex index(a);
  const std::vector<place::Landmark> b{at(0.5, 0, 0.8),   // 0.94 m apart in 3-D: a match (0.5 m across, 0.8 m up)
                                at(10.1, 0, 1.2),  // 1.2 m higher: no match
                                at(20.7, 0, 0)};   // 0.7 m across: no match
  const place::VerifyParams p;  // 0.6 m horizontal, 1.0 m vertical
  const std::vector<place::LandmarkMatch> m = place::guidedMatches(a, index, b, Pose::Identity(), p);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].a, 0u);
  EXPECT_EQ(m[0].b, 0u);
}

TEST(Verify, ARivalIsAnotherAlignmentElsewhere) {
  std::vector<place::Landmark> b;
  for (int i = 0; i < 10; ++i) b.push_back(at(i, 0, 0));
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < 10; ++i) pairs.emplace_back(i, i);
  place::PlaceResult best = withInliers(Pose::Identity(), pairs);
  best.covered = 10;
  const place::VerifyParams p;
  // The same alignment found again, and a variant 1 m off sharing none of the matches: no rival.
  const place::PlaceResult same = best;
  std::vector<std::pair<std::size_t, std::size_t>> other;
  for (std::size_t i = 0; i < 6; ++i) other.emplace_back(100 + i, i);
  place::PlaceResult near = withInliers(poseFromXyzYaw(1.0, 0, 0, 0), other);
  near.covered = 8;
  EXPECT_EQ(place::rivalOf(best, {best, same, near}, b, p), nullptr);
  // 10 m off, or turned by 10 degrees about the matches' centroid: rivals, accepted or not.
  place::PlaceResult far = near;
  far.T_a_b = poseFromXyzYaw(10.0, 0, 0, 0);
  const std::vector<place::PlaceResult> with_far{best, far};
  ASSERT_NE(place::rivalOf(best, with_far, b, p), nullptr);
  EXPECT_EQ(place::rivalOf(best, with_far, b, p)->inliers.size(), 6u);
  place::PlaceResult rejected = far;
  rejected.found = false;
  EXPECT_NE(place::rivalOf(best, {best, rejected}, b, p), nullptr);
  place::PlaceResult turned = near;
  turned.T_a_b = poseFromXyzYaw(4.5, 0, 0, 0) * poseFromXyzYaw(0, 0, 0, 10 * M_PI / 180) * poseFromXyzYaw(-4.5, 0, 0, 0);
  EXPECT_NE(place::rivalOf(best, {best, turned}, b, p), nullptr);

  // Strength: support times the support's fraction of the covered landmarks.
  EXPECT_DOUBLE_EQ(place::strengthOf(best), 10.0);
  EXPECT_DOUBLE_EQ(place::strengthOf(far), 4.5);
  place::PlaceResult loose = best;
  loose.support = 5.0;  // ten matches spread over the match disc
  EXPECT_DOUBLE_EQ(place::strengthOf(loose), 10.0);
  EXPECT_DOUBLE_EQ(place::strengthOf(loose, true), 2.5);
  place::PlaceResult stands = best;
  EXPECT_TRUE(place::standsAgainstRival(&far, p, stands));  // 10 >= 2 x 4.5
  EXPECT_TRUE(place::standsAgainstRival(nullptr, p, stands));
  place::PlaceResult falls = best;
  place::PlaceResult strong = far;
  strong.covered = 6;  // 6 of 6: strength 6
  EXPECT_FALSE(place::standsAgainstRival(&strong, p, falls));
  EXPECT_FALSE(falls.found);
  EXPECT_NE(falls.reason.find("ambiguous"), std::string::npos);
}

// Each match weighs 1 - (d / match radius)^2 for its horizontal residual d after refinement: 40
// landmarks on a circle matched to a circle 0.3 m wider (no rigid transform takes the offsets out)
// support 40 x 0.75; matched to themselves, 40. The fit decides the ambiguity test only when it is
// significantly tighter than chance's (mean weight 1/2): at 40 matches, a mean weight of 0.728.
TEST(Verify, SupportWeighsEachMatchByItsFit) {
  auto circle = [](double radius) {
    std::vector<place::Landmark> c;
    for (int k = 0; k < 40; ++k) c.push_back(at(radius * std::cos(k * M_PI / 20), radius * std::sin(k * M_PI / 20), 0, 71, c.size()));
    return c;
  };
  const std::vector<place::Landmark> b = circle(10.0);
  const place::LandmarkIndex index_b(b);
  const place::VerifyParams p;  // 0.6 m radius, significance 5
  auto verified = [&](double radius) {
    const std::vector<place::Landmark> a = circle(radius);
    place::PlaceResult r;
    place::refineAndDecide(a, place::LandmarkIndex(a), b, index_b, Pose::Identity(), p, r);
    EXPECT_EQ(r.inliers.size(), 40u);
    return r;
  };
  const place::PlaceResult exact = verified(10.0), loose = verified(10.3), looser = verified(10.4);
  EXPECT_NEAR(exact.support, 40.0, 1e-9);
  EXPECT_NEAR(loose.support, 40 * (1 - 0.09 / 0.36), 1e-6);
  EXPECT_NEAR(looser.support, 40 * (1 - 0.16 / 0.36), 1e-6);
  EXPECT_DOUBLE_EQ(place::strengthOf(exact), place::strengthOf(looser)) << "by count they are alike";
  EXPECT_LT(place::strengthOf(looser, true), 0.35 * place::strengthOf(exact, true));
  EXPECT_TRUE(place::fitDecides(exact, p));
  EXPECT_TRUE(place::fitDecides(loose, p));
  EXPECT_FALSE(place::fitDecides(looser, p));
}

// Two rooms furnished alike: B saw one of them; either would fit, so no transform may be given.
TEST(Verify, TwoRoomsFurnishedAlikeGiveNoTransform) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 8);
  std::vector<place::Landmark> room;
  const int classes[] = {1, 1, 2, 3};
  for (int i = 0; i < 24; ++i) room.push_back(at(u(rng), u(rng), 0.5, classes[i % 4]));
  std::vector<place::Landmark> a;
  for (double dx : {0.0, 20.0})
    for (place::Landmark l : room) {
      l.p.x() += dx;
      l.index = a.size();
      a.push_back(l);
    }
  const Pose truth = poseFromXyzYaw(3.0, -2.0, 0.1, 0.7);
  std::vector<place::Landmark> first_room(a.begin(), a.begin() + 24);
  const std::vector<place::Landmark> b =
      place::perturbedCopy(first_room, truth, place::PerturbParams{0.03, 0.0, 0.0}, rng);
  const place::PlaceResult m = place::slideMatch(a, b, place::SlideMatchParams{});
  EXPECT_FALSE(m.found) << eval::transformError(m.T_a_b, truth).translation_m;
  EXPECT_NE(m.reason.find("ambiguous"), std::string::npos) << m.reason;
  const place::PlaceResult g = place::slideGraph(a, b, place::SlideGraphParams{});
  EXPECT_FALSE(g.found) << eval::transformError(g.T_a_b, truth).translation_m;
  // With most of the other room rearranged, the room B saw stands out: a transform, the right one.
  for (std::size_t k = 24; k < 42; ++k) a[k].p += Eigen::Vector3d(k % 2 ? 2.5 : -2.0, k % 3 ? 1.5 : -2.5, 0);
  const place::PlaceResult m2 = place::slideMatch(a, b, place::SlideMatchParams{});
  ASSERT_TRUE(m2.found) << m2.reason;
  EXPECT_LT(eval::transformError(m2.T_a_b, truth).translation_m, 0.2);
}

// A camera robot maps only the trunks near its path that its detector caught; a LiDAR robot maps
// every trunk around the same path. The overlap is what the sparser map holds there: the right
// alignment is accepted whichever robot checks (counted over the dense map's landmarks around the
// sparse one's, the camera robot would reject it).
TEST(Verify, ASparseMapAlignsWithADenseOneInEitherRole) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ux(-10, 70), uy(-20, 20);
  std::normal_distribution<double> noise(0, 0.08);
  std::vector<place::Landmark> dense, sparse;
  const Pose truth = poseFromXyzYaw(4.0, -3.0, 0.2, 0.4);  // T_dense_sparse
  const Pose T_sparse_dense = truth.inverse();
  for (int i = 0; i < 200; ++i) {
    const double x = ux(rng), y = uy(rng);
    dense.push_back(at(x + noise(rng), y + noise(rng), 1.0, 71, dense.size()));
    // The camera saw it: within 6 m of the path (y = 0, x in 0..60), and one in three detected.
    if (x >= 0 && x <= 60 && std::abs(y) <= 6 && i % 3 == 0) {
      place::Landmark l = at(x + noise(rng), y + noise(rng), 1.0, 71, sparse.size());
      l.p = T_sparse_dense * l.p;
      sparse.push_back(l);
    }
  }
  ASSERT_GE(sparse.size(), 12u);
  const place::VerifyParams p;
  const place::LandmarkIndex index_dense(dense), index_sparse(sparse);
  place::PlaceResult sparse_checks, dense_checks;
  place::refineAndDecide(sparse, index_sparse, dense, index_dense, T_sparse_dense, p, sparse_checks);
  place::refineAndDecide(dense, index_dense, sparse, index_sparse, truth, p, dense_checks);
  EXPECT_TRUE(sparse_checks.found) << sparse_checks.reason;
  EXPECT_TRUE(dense_checks.found) << dense_checks.reason;
  // Counted over the dense map's landmarks around the sparse one's, the matches fall short of 0.2.
  const place::Overlap ov = place::overlapOf(sparse, index_sparse, dense, T_sparse_dense, p.match_radius);
  const std::size_t covered_sparse = place::coveredBy(sparse, truth, index_dense, p.match_radius);
  EXPECT_LE(covered_sparse, sparse.size());
  EXPECT_GT(ov.covered, 4 * covered_sparse);
  EXPECT_LT(static_cast<double>(sparse_checks.inliers.size()), p.min_inlier_ratio * static_cast<double>(ov.covered));
  // And a transform found by the place-recognition methods, from the camera robot's side.
  const place::PlaceResult g = place::slideGraph(sparse, dense, place::SlideGraphParams{});
  ASSERT_TRUE(g.found) << g.reason;
  EXPECT_LT(eval::transformError(g.T_a_b, T_sparse_dense).translation_m, 0.3);
}

// Six trunks a metre or two apart, seen with 0.2 m of noise, fix a shift but not the yaw (its
// standard error is about 3 deg): no transform. Spread over 20 m the same noise fixes it within half a degree.
TEST(Verify, MatchesThatCannotFixTheYawGiveNoTransform) {
  const auto ring = [](double radius) {
    std::vector<place::Landmark> out;
    for (int k = 0; k < 6; ++k)
      out.push_back(at(radius * std::cos(k * M_PI / 3), radius * std::sin(k * M_PI / 3 + 0.3 * (k % 2)), 0, 71, k));
    return out;
  };
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 0.2);
  for (const double radius : {1.5, 10.0}) {
    const std::vector<place::Landmark> a = ring(radius);
    std::vector<place::Landmark> b = a;
    for (place::Landmark& l : b) l.p += Eigen::Vector3d(noise(rng), noise(rng), 0);
    const place::LandmarkIndex ia(a), ib(b);
    place::PlaceResult r;
    place::refineAndDecide(a, ia, b, ib, Pose::Identity(), place::VerifyParams{}, r);
    EXPECT_EQ(r.inliers.size(), 6u) << radius;
    if (radius < 5) {
      EXPECT_FALSE(r.found);
      EXPECT_NE(r.reason.find("fix its yaw only to"), std::string::npos) << r.reason;
    } else {
      EXPECT_TRUE(r.found) << r.reason;
    }
  }
}

// The grid behind the radius queries returns exactly the landmarks a brute-force scan finds,
// with a far stray landmark stretching the extent (the grid coarsens instead of growing).
TEST(LandmarkIndex, RadiusQueriesMatchBruteForce) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-30, 30), h(-2, 2);
  std::vector<place::Landmark> lms;
  for (int i = 0; i < 600; ++i) {
    place::Landmark l = at(u(rng), u(rng), h(rng));
    l.class_id = i % 3;
    lms.push_back(l);
  }
  lms.push_back(at(5e6, -5e6, 0));
  const place::LandmarkIndex index(lms);
  for (int q = 0; q < 300; ++q) {
    const Eigen::Vector3d p(u(rng), u(rng), h(rng));
    const double r = q % 2 ? 1.2 : 4.5;
    const int cls = q % 4 == 3 ? place::LandmarkIndex::kAnyClass : q % 4;
    std::vector<std::size_t> expect;
    for (std::size_t i = 0; i < lms.size(); ++i)
      if ((cls == place::LandmarkIndex::kAnyClass || lms[i].class_id == cls) && (lms[i].p - p).norm() <= r)
        expect.push_back(i);
    std::vector<std::size_t> got = index.radius(p, r, cls);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, expect);
    EXPECT_EQ(index.countWithin(p, r, cls), expect.size());
  }
}
