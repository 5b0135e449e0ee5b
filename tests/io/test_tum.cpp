#include <gtest/gtest.h>

#include <fstream>

#include "io/io_error.h"
#include "io/tum_trajectory.h"

using namespace slide;

TEST(Tum, RoundTripAndErrors) {
  const std::string path = testing::TempDir() + "traj.tum";
  const std::vector<StampedPose> traj = {{0.5, poseFromXyzYaw(1, 2, 3, 0.3)}, {1.5, poseFromXyzYaw(4, 5, 6, -1.0)}};
  io::writeTum(path, traj);
  const auto back = io::readTum(path);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_DOUBLE_EQ(back[1].t, 1.5);
  EXPECT_TRUE(back[1].pose.isApprox(traj[1].pose, 1e-8));

  std::ofstream(path) << "# comment\n0 1 2 3 0 0 0 1\n1 1 2 x 0 0 0 1\n";
  try {
    io::readTum(path);
    FAIL();
  } catch (const io::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
  std::ofstream(path) << "0 1 2 3 0 0 0 2\n";
  EXPECT_THROW(io::readTum(path), io::IoError);
  std::ofstream(path) << "2 1 2 3 0 0 0 1\n1 1 2 3 0 0 0 1\n";
  EXPECT_THROW(io::readTum(path), io::IoError);
}
