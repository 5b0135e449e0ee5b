#include <gtest/gtest.h>

#include "objects/association.h"

using namespace slide;

namespace {
Object car(double x, double y, double yaw, Eigen::Vector3d dims = {4.5, 1.8, 1.5}) {
  Object o;
  o.class_id = 10;
  o.model = Cuboid{poseFromXyzYaw(x, y, 0.75, yaw), dims};
  return o;
}
Object trunk(Eigen::Vector3d root, double r, Eigen::Vector3d axis = Eigen::Vector3d::UnitZ(), double len = 4) {
  Object o;
  o.class_id = 71;
  o.model = Cylinder{root, axis.normalized(), r, len};
  return o;
}
Object chair(Eigen::Vector3d c) {
  Object o;
  o.class_id = 1;
  o.model = Ellipsoid{c, 0.3, 0.9};
  return o;
}
}  // namespace

TEST(Objects, TransformCuboidByPose) {
  // Car at (2, 0) facing +x, seen from a robot at (10, 5) facing +y (yaw 90 deg):
  // in the world it lies at (10, 7) facing +y.
  const Pose T_world_body = poseFromXyzYaw(10, 5, 0, M_PI / 2);
  const Object w = transformObject(T_world_body, car(2, 0, 0));
  const auto& c = std::get<Cuboid>(w.model);
  EXPECT_TRUE(c.pose.translation().isApprox(Eigen::Vector3d(10, 7, 0.75), 1e-12));
  EXPECT_NEAR(yawOf(c.pose.linear()), M_PI / 2, 1e-12);
  EXPECT_TRUE(c.dims.isApprox(Eigen::Vector3d(4.5, 1.8, 1.5)));
}

TEST(Objects, TransformCylinderAndEllipsoid) {
  const Pose T = poseFromXyzYaw(1, 2, 3, M_PI);
  const Object t = transformObject(T, trunk({1, 0, 0}, 0.2, {1, 0, 1}));
  const auto& c = std::get<Cylinder>(t.model);
  EXPECT_TRUE(c.root.isApprox(Eigen::Vector3d(0, 2, 3), 1e-12));
  EXPECT_TRUE(c.axis.isApprox(Eigen::Vector3d(-1, 0, 1).normalized(), 1e-12));
  EXPECT_DOUBLE_EQ(c.radius, 0.2);
  const Object e = transformObject(T, chair({0, 1, 0}));
  EXPECT_TRUE(e.position().isApprox(Eigen::Vector3d(1, 1, 3), 1e-12));
}

TEST(Objects, PositionAndExtent) {
  const Object t = trunk({0, 0, 0}, 0.25, Eigen::Vector3d::UnitZ(), 6);
  EXPECT_TRUE(t.position().isApprox(Eigen::Vector3d(0, 0, 3)));
  EXPECT_TRUE(t.extent().isApprox(Eigen::Vector3d(0.5, 0.5, 6)));
  EXPECT_TRUE(chair({1, 1, 1}).extent().isApprox(Eigen::Vector3d(0.6, 0.6, 0.9)));
  EXPECT_EQ(car(0, 0, 0).shape(), Shape::Cuboid);
  Object bad = chair({NAN, 0, 0});
  EXPECT_FALSE(bad.isFinite());
}

TEST(Objects, AssociationDistances) {
  EXPECT_NEAR(associationDistance(car(0, 0, 0), car(3, 4, 0)), 5.0, 1e-12);
  // Two views of one vertical trunk at different heights: distance to the axis is zero.
  EXPECT_NEAR(associationDistance(trunk({5, 5, 0}, 0.2), trunk({5, 5, 2}, 0.2, Eigen::Vector3d::UnitZ(), 1)), 0, 1e-12);
  EXPECT_NEAR(associationDistance(trunk({0, 0, 0}, 0.2), trunk({0.6, 0.8, 0}, 0.2)), 1.0, 1e-12);
  // Length and width swapped is the same car.
  EXPECT_NEAR(modelDifference(car(0, 0, 0, {4.5, 1.8, 1.5}), car(0, 0, 0, {1.8, 4.5, 1.5})), 0, 1e-12);
  EXPECT_NEAR(modelDifference(car(0, 0, 0, {4.5, 1.8, 1.5}), car(0, 0, 0, {4.0, 1.8, 1.5})), 0.5, 1e-12);
  EXPECT_NEAR(modelDifference(trunk({0, 0, 0}, 0.2), trunk({0, 0, 0}, 0.35)), 0.15, 1e-12);
  EXPECT_TRUE(std::isinf(modelDifference(car(0, 0, 0), chair({0, 0, 0}))));
}

TEST(Objects, FootprintsOverlap) {
  const auto box = [](const Object& o) { return std::get<Cuboid>(o.model); };
  // Side by side (1.8 m wide, 2.5 m apart): apart; 0.35 m of margin each closes the 0.7 m gap.
  EXPECT_FALSE(footprintsOverlap(box(car(0, 0, M_PI / 2)), box(car(2.5, 0, M_PI / 2))));
  EXPECT_TRUE(footprintsOverlap(box(car(0, 0, M_PI / 2)), box(car(2.5, 0, M_PI / 2)), 0.36));
  EXPECT_FALSE(footprintsOverlap(box(car(0, 0, M_PI / 2)), box(car(2.5, 0, M_PI / 2)), 0.34));
  // Nose to tail along the length: 4.4 m apart overlaps, 4.6 m does not.
  EXPECT_TRUE(footprintsOverlap(box(car(0, 0, 0)), box(car(4.4, 0, 0))));
  EXPECT_FALSE(footprintsOverlap(box(car(0, 0, 0)), box(car(4.6, 0, 0))));
  // Crossed boxes: only the diagonal gap counts (separating axis of the rotated box).
  EXPECT_TRUE(footprintsOverlap(box(car(0, 0, 0)), box(car(2.5, 2.0, M_PI / 4))));
  EXPECT_FALSE(footprintsOverlap(box(car(0, 0, 0)), box(car(3.0, 3.5, M_PI / 4))));
}

