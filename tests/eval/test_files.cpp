#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "eval/stage_timing.h"
#include "eval/trajectory_file.h"
#include "io/io_error.h"
#include "io/kitti_poses.h"

using namespace slide;
namespace fs = std::filesystem;

namespace {
class Files : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("slide_eval_files_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const std::string p = (dir_ / name).string();
    std::ofstream(p) << text;
    return p;
  }
  fs::path dir_;
};
}  // namespace

TEST_F(Files, TrajectoryFormatsAreDetected) {
  const auto tum = write("t.txt", "# t x y z qx qy qz qw\n0.5 1 2 3 0 0 0 1\n1.5 2 2 3 0 0 0 1\n");
  const auto a = eval::readTrajectory(tum);
  ASSERT_EQ(a.size(), 2u);
  EXPECT_DOUBLE_EQ(a[1].t, 1.5);
  const std::string kitti = (dir_ / "k.txt").string();
  io::writeKittiPoses(kitti, {poseFromXyzYaw(1, 0, 0, 0), poseFromXyzYaw(2, 0, 0, 0), poseFromXyzYaw(3, 0, 0, 0)});
  const auto k = eval::readTrajectory(kitti);
  ASSERT_EQ(k.size(), 3u);
  EXPECT_DOUBLE_EQ(k[2].t, 2.0);
  EXPECT_DOUBLE_EQ(k[2].pose.translation().x(), 3.0);
  const auto times = write("times.txt", "0.0\n0.1\n0.2\n");
  EXPECT_DOUBLE_EQ(eval::readTrajectory(kitti, eval::TrajectoryFormat::Kitti, times)[1].t, 0.1);
  const auto short_times = write("short.txt", "0.0\n");
  EXPECT_THROW(eval::readTrajectory(kitti, eval::TrajectoryFormat::Auto, short_times), io::IoError);
  EXPECT_THROW(eval::readTrajectory(write("bad.txt", "1 2 3\n")), io::IoError);
  EXPECT_THROW(eval::parseTrajectoryFormat("evo"), std::invalid_argument);
}

TEST_F(Files, StageSamples) {
  const auto p = write("s.txt", "# timings\nfit 2.0\nfit 4.0\nupdate 1.5\n");
  const auto s = eval::readStageSamples(p);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.at("fit").size(), 2u);
  EXPECT_THROW(eval::readStageSamples(write("bad_s.txt", "fit two\n")), io::IoError);
  EXPECT_EQ(eval::readStageSamples(write("plain.txt", "1\n2\n")).at("all").size(), 2u);
}
