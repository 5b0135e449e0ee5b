#include <gtest/gtest.h>

#include <random>

#include "place/neighbourhood.h"

using namespace slide;

namespace {
std::vector<place::Landmark> forest(int n, double w, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, w);
  std::vector<place::Landmark> out;
  for (int i = 0; i < n; ++i) {
    place::Landmark l;
    l.p = {u(rng), u(rng), 0};
    l.class_id = i % 5 ? 71 : 80;
    l.index = i;
    out.push_back(l);
  }
  return out;
}

std::vector<place::Landmark> moved(std::vector<place::Landmark> lms, const Pose& T) {
  for (place::Landmark& l : lms) l.p = T * l.p;
  return lms;
}
}  // namespace

TEST(Neighbourhoods, NeighboursAreThoseWithinTheRadiusSortedByDistance) {
  const std::vector<place::Landmark> lms = forest(300, 60, 3);
  const place::Neighbourhoods n(lms, 8.0);
  ASSERT_EQ(n.size(), lms.size());
  for (std::size_t i = 0; i < lms.size(); i += 7) {
    std::size_t expect = 0;
    for (std::size_t j = 0; j < lms.size(); ++j)
      expect += j != i && (lms[j].p - lms[i].p).head<2>().norm() <= 8.0;
    ASSERT_EQ(static_cast<std::size_t>(n.end(i) - n.begin(i)), expect);
    for (const auto* k = n.begin(i); k + 1 < n.end(i); ++k) EXPECT_LE(k->dist, (k + 1)->dist);
  }
}

// The descriptor does not change when the map is turned and moved; the local yaw vote of a
// landmark with itself in the moved map finds the turn.
TEST(Neighbourhoods, DescriptorIsRotationInvariantAndTheLocalYawFindsTheTurn) {
  const std::vector<place::Landmark> a = forest(400, 60, 5);
  const Pose T = poseFromXyzYaw(-40, 17, 0.3, 2.0);  // maps a's frame into b's
  const std::vector<place::Landmark> b = moved(a, T);
  const place::Neighbourhoods na(a, 12.0), nb(b, 12.0);
  int checked = 0;
  for (std::size_t i = 0; i < a.size(); i += 11) {
    EXPECT_LT((na.descriptor(i) - nb.descriptor(i)).norm(), 1e-3) << i;
    if (na.end(i) - na.begin(i) < 10) continue;
    // T_a_b turns b onto a: the inverse of the turn above.
    const place::LocalYaw ly = place::localYaw(na, i, nb, i, 0.3, 1.5, 3.0 * M_PI / 180.0);
    EXPECT_GE(ly.votes, 8);
    EXPECT_NEAR(wrapAngle(ly.yaw + 2.0), 0.0, 0.01) << i;
    ++checked;
  }
  EXPECT_GT(checked, 20);
  // Different places of one forest mostly disagree.
  int weak = 0, pairs = 0;
  for (std::size_t i = 0; i + 50 < a.size(); i += 13, ++pairs)
    weak += place::localYaw(na, i, nb, i + 50, 0.3, 1.5, 3.0 * M_PI / 180.0).votes <
            place::localYaw(na, i, nb, i, 0.3, 1.5, 3.0 * M_PI / 180.0).votes / 2;
  EXPECT_GT(weak, pairs * 3 / 4);
}
