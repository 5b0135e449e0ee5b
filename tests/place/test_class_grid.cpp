#include <gtest/gtest.h>

#include <random>

#include "place/class_grid.h"

using namespace slide;

TEST(ClassGrid, NearestWithinMatchesBruteForce) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-20, 20), s(0.2, 2.0);
  std::vector<place::Landmark> lms;
  for (int i = 0; i < 400; ++i) {
    place::Landmark l;
    l.p = {u(rng), u(rng), 0};
    l.class_id = i % 3;
    l.size = i % 5 ? Eigen::Vector3d(s(rng), s(rng), 1.0) : Eigen::Vector3d::Zero();
    lms.push_back(l);
  }
  const place::ClassGrid grid(lms, 0.6);
  for (int q = 0; q < 500; ++q) {
    const double x = u(rng), y = u(rng), r = q % 2 ? 0.6 : 1.7;
    const int cls = q % 4;  // class 3 is absent
    const Eigen::Vector3d size(s(rng), s(rng), 1.0);
    long expect = -1;
    double best = r * r;
    for (std::size_t i = 0; i < lms.size(); ++i) {
      const double d2 = std::pow(lms[i].p.x() - x, 2) + std::pow(lms[i].p.y() - y, 2);
      if (lms[i].class_id == cls && d2 <= best && place::sizesAgree(lms[i].size, size, 0.5)) {
        best = d2;
        expect = static_cast<long>(i);
      }
    }
    EXPECT_EQ(grid.nearestWithin(cls, x, y, r, size, 0.5), expect) << "query " << q;
  }
}

TEST(Landmark, SizesAgreeWithSwappedLengthAndWidthOrUnknownSize) {
  EXPECT_TRUE(place::sizesAgree({4.5, 1.8, 1.5}, {1.8, 4.5, 1.5}, 0.1));
  EXPECT_FALSE(place::sizesAgree({4.5, 1.8, 1.5}, {0.5, 0.5, 1.5}, 1.0));
  EXPECT_TRUE(place::sizesAgree({4.5, 1.8, 1.5}, Eigen::Vector3d::Zero(), 0.1));
}
