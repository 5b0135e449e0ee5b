// Trajectory figures that are finite but mean little carry a warning: a collapsed or exploded
// sim3 scale, and an association covering few reference poses.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "eval/trajectory_warnings.h"

using namespace slide;

TEST(TrajectoryWarnings, ScaleOutsideHalfToTwoOrNotFiniteWarns) {
  EXPECT_FALSE(eval::scaleWarning(1.0));
  EXPECT_FALSE(eval::scaleWarning(0.6));
  EXPECT_FALSE(eval::scaleWarning(1.9));
  ASSERT_TRUE(eval::scaleWarning(1e-4));
  EXPECT_NE(eval::scaleWarning(1e-4)->find("shrank"), std::string::npos) << *eval::scaleWarning(1e-4);
  EXPECT_NE(eval::scaleWarning(3.0)->find("stretched"), std::string::npos);
  EXPECT_TRUE(eval::scaleWarning(0.0));
  EXPECT_TRUE(eval::scaleWarning(std::numeric_limits<double>::quiet_NaN()));
}

TEST(TrajectoryWarnings, CoverageIsJudgedAgainstTheReferenceCount) {
  // 3 of 3 estimate poses matched, but the reference has 501: a warning naming both counts.
  const auto w = eval::coverageWarning(3, 3, 501);
  ASSERT_TRUE(w);
  EXPECT_NE(w->find("only 3 of 501 reference poses"), std::string::npos) << *w;
  // Stamps that do not line up: few pairs of two long trajectories.
  ASSERT_TRUE(eval::coverageWarning(10, 500, 501));
  EXPECT_NE(eval::coverageWarning(10, 500, 501)->find("matched in time"), std::string::npos);
  EXPECT_FALSE(eval::coverageWarning(480, 500, 501));
  EXPECT_FALSE(eval::coverageWarning(110, 110, 501));  // a key-pose estimate covering a fifth of the reference
}
