#include <gtest/gtest.h>

#include <cmath>

#include "eval/placed_file.h"

using namespace slide;

TEST(PlacedFile, PathWithAndWithoutPlacement) {
  const eval::PlacedFile plain = eval::parsePlacedFile("maps/robot0.txt");
  EXPECT_EQ(plain.path, "maps/robot0.txt");
  EXPECT_TRUE(plain.placement.isApprox(Pose::Identity()));
  const eval::PlacedFile placed = eval::parsePlacedFile("a@b/robot1.txt@1,2.5,-3,90");
  EXPECT_EQ(placed.path, "a@b/robot1.txt");
  EXPECT_TRUE(placed.placement.translation().isApprox(Eigen::Vector3d(1, 2.5, -3)));
  EXPECT_NEAR(yawOf(placed.placement.linear()), M_PI / 2, 1e-12);
  EXPECT_EQ(eval::parsePlacedFile("runs/a@b/map.txt").path, "runs/a@b/map.txt");
  EXPECT_THROW(eval::parsePlacedFile("robot.txt@1,2,3"), std::invalid_argument);
  EXPECT_THROW(eval::parsePlacedFile("robot.txt@1,2,3,x"), std::invalid_argument);
  EXPECT_THROW(eval::parsePlacedFile("@1,2,3,4"), std::invalid_argument);
}
