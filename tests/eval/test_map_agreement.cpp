#include <gtest/gtest.h>

#include "eval/map_agreement.h"

using namespace slide;

namespace {
Object at(int cls, const Eigen::Vector3d& p) {
  Object o;
  o.class_id = cls;
  o.model = Ellipsoid{p, 0.3, 0.5};
  return o;
}
}  // namespace

// Two robots map four of five real objects each, three of them in common, in their own frames;
// robot b's copy of one common object is 0.2 m off. The alignment takes only the common three,
// and the distances after it show the offset where it is.
TEST(MapAgreement, AlignsOverTheObjectsBothMapsHold) {
  const std::vector<Object> truth{at(10, {0, 0, 0}), at(10, {10, 0, 0}), at(71, {0, 8, 0}), at(71, {20, 5, 0}),
                                  at(71, {-10, -4, 0})};
  const Pose T_w_a = poseFromXyzYaw(1, 2, 0, 0.3), T_w_b = poseFromXyzYaw(-5, 3, 0.5, -1.2);
  auto in = [](const Pose& T_w, const Eigen::Vector3d& p) { return T_w.inverse() * p; };
  const std::vector<Object> map_a{at(10, in(T_w_a, {0, 0, 0})), at(10, in(T_w_a, {10, 0, 0})),
                                  at(71, in(T_w_a, {0, 8, 0})), at(71, in(T_w_a, {20, 5, 0}))};
  const std::vector<Object> map_b{at(10, in(T_w_b, {0.2, 0, 0})), at(10, in(T_w_b, {10, 0, 0})),
                                  at(71, in(T_w_b, {0, 8, 0})), at(71, in(T_w_b, {-10, -4, 0}))};
  eval::ObjectMatchOptions mo;
  mo.threshold = 1.0;
  const eval::SharedLandmarks sh = eval::sharedLandmarks(map_a, T_w_a, map_b, T_w_b, truth, mo);
  ASSERT_EQ(sh.in_a.size(), 3u);
  const std::optional<Pose> T = eval::mapAlignment(sh);
  ASSERT_TRUE(T);
  const eval::HorizontalError e = eval::horizontalError(*T, T_w_a.inverse() * T_w_b);
  EXPECT_LT(e.translation_m, 0.2);
  EXPECT_GT(e.translation_m, 0.01);  // the 0.2 m offset pulls the alignment a little
  EXPECT_LT(e.yaw_deg, 2.0);
  // Heights do not count: robot b's landmarks 1 m higher give the same horizontal alignment.
  eval::SharedLandmarks higher = sh;
  for (Eigen::Vector3d& p : higher.in_b) p.z() += 1.0;
  const std::optional<Pose> T2 = eval::mapAlignment(higher);
  ASSERT_TRUE(T2);
  EXPECT_NEAR(eval::horizontalError(*T2, *T).translation_m, 0.0, 1e-9);
  const std::vector<double> d = eval::landmarkDistances(sh, T_w_a.inverse() * T_w_b);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_NEAR(d[0], 0.2, 1e-9);  // the true transform shows the offset in full
  EXPECT_NEAR(d[1], 0.0, 1e-9);
  EXPECT_NEAR(d[2], 0.0, 1e-9);
  // Classes pair landmarks too: with b's trunks called cars only one object is common.
  std::vector<Object> b_cars = map_b;
  for (Object& o : b_cars) o.class_id = 10;
  EXPECT_FALSE(eval::mapAlignment(eval::sharedLandmarks(map_a, T_w_a, b_cars, T_w_b, truth, mo)));
}
