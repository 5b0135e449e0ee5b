#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "io/kitti_poses.h"
#include "io/tum_trajectory.h"
#include "report/json.h"

using namespace slide;
namespace fs = std::filesystem;

// slide-eval and slide-plot end to end on small TUM, KITTI and map files.
class EvalCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("slide_eval_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  int run(const std::string& tool, const std::string& args) const {
    const std::string cmd = std::string(SLIDE_BINARY_DIR) + "/bin/" + tool + " " + args + " --log-level warn > '" +
                            path("out.txt") + "' 2>&1";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string output() const {
    std::ifstream in(path("out.txt"));
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  fs::path dir_;
};

TEST_F(EvalCli, AteOfTumAgainstKittiWithHandComputedError) {
  // Reference: KITTI poses along x, one per frame (times = frame index). Estimate: TUM with
  // the same stamps, every pose 0.3 m off in y except the first; no alignment -> rmse
  // sqrt(3 * 0.09 / 4) = 0.2598.
  std::vector<Pose> ref;
  std::vector<StampedPose> est;
  for (int i = 0; i < 4; ++i) {
    ref.push_back(poseFromXyzYaw(i, 0, 0, 0));
    est.push_back({double(i), poseFromXyzYaw(i, i ? 0.3 : 0.0, 0, 0)});
  }
  io::writeKittiPoses(path("ref.txt"), ref);
  io::writeTum(path("est.tum"), est);
  ASSERT_EQ(run("slide-eval", "ate " + path("est.tum") + " " + path("ref.txt") + " --align none --json " + path("a.json")), 0)
      << output();
  const report::Json j = report::readJsonFile(path("a.json"));
  EXPECT_EQ(j.at("pairs").get<double>(), 4);
  EXPECT_NEAR(j.at("translation_m").at("rmse").get<double>(), std::sqrt(3 * 0.09 / 4), 1e-6);
  EXPECT_NE(output().find("rmse 0.2598 m"), std::string::npos) << output();
  // RPE over 1 frame: errors 0.3, 0, 0.
  ASSERT_EQ(run("slide-eval", "rpe " + path("est.tum") + " " + path("ref.txt") + " --json " + path("r.json")), 0) << output();
  EXPECT_NEAR(report::readJsonFile(path("r.json")).at("translation_m").at("max").get<double>(), 0.3, 1e-6);
  // A bad file gives a clear error naming it, and exit code 1.
  std::ofstream(path("bad.txt")) << "1 2 3\n";
  EXPECT_EQ(run("slide-eval", "ate " + path("bad.txt") + " " + path("ref.txt")), 1);
  EXPECT_NE(output().find(path("bad.txt")), std::string::npos) << output();
}

TEST_F(EvalCli, CollapsedSim3ScaleAndFewReferencePosesWarnInTheJson) {
  // Reference: 501 poses along x. Estimate: 3 poses ten times as far apart: sim3 shrinks it
  // (scale 0.1) and only 3 of 501 reference poses are associated.
  std::vector<StampedPose> ref, est;
  for (int i = 0; i <= 500; ++i) ref.push_back({0.1 * i, poseFromXyzYaw(0.2 * i, 0, 0, 0)});
  for (int i : {0, 250, 500}) est.push_back({0.1 * i, poseFromXyzYaw(2.0 * i, 0, 0, 0)});
  io::writeTum(path("ref.tum"), ref);
  io::writeTum(path("est.tum"), est);
  ASSERT_EQ(run("slide-eval", "ate " + path("est.tum") + " " + path("ref.tum") + " --align sim3 --json " + path("a.json")),
            0)
      << output();
  const report::Json j = report::readJsonFile(path("a.json"));
  EXPECT_NEAR(j.at("scale").get<double>(), 0.1, 1e-6);
  const report::Json& w = j.at("warnings");
  ASSERT_EQ(w.size(), 2u) << j.dump();
  EXPECT_NE(w[0].get<std::string>().find("only 3 of 501 reference poses"), std::string::npos) << j.dump();
  EXPECT_NE(w[1].get<std::string>().find("sim3 scale"), std::string::npos) << j.dump();
  EXPECT_NE(output().find("WARNING: sim3 scale"), std::string::npos) << output();
  // The same files under se3 keep only the coverage warning; a full, sane run has none.
  ASSERT_EQ(run("slide-eval", "ate " + path("est.tum") + " " + path("ref.tum") + " --json " + path("b.json")), 0);
  EXPECT_EQ(report::readJsonFile(path("b.json")).at("warnings").size(), 1u);
  ASSERT_EQ(run("slide-eval", "ate " + path("ref.tum") + " " + path("ref.tum") + " --align sim3 --json " + path("c.json")),
            0);
  EXPECT_TRUE(report::readJsonFile(path("c.json")).at("warnings").empty());
}

TEST_F(EvalCli, ObjectsTransformAndPlots) {
  std::ofstream(path("gt.txt")) << "-2 0 0 0.8\n-2 10 0 0.8\n-1 5 5 2\n";
  std::ofstream(path("est.txt")) << "-2 0.4 0 0.8\n-1 5 5.2 2\n3 40 40 1\n";
  ASSERT_EQ(run("slide-eval", "objects " + path("est.txt") + " " + path("gt.txt") + " --json " + path("o.json")), 0)
      << output();
  const report::Json o = report::readJsonFile(path("o.json"));
  EXPECT_NEAR(o.at("overall").at("precision").get<double>(), 2.0 / 3, 1e-9);
  EXPECT_NEAR(o.at("overall").at("recall").get<double>(), 2.0 / 3, 1e-9);
  EXPECT_NEAR(o.at("overall").at("position_rmse_m").get<double>(), std::sqrt((0.16 + 0.04) / 2), 1e-9);
  // --list names every match, false positive and miss.
  ASSERT_EQ(run("slide-eval", "objects " + path("est.txt") + " " + path("gt.txt") + " --list --json " + path("l.json")), 0);
  const report::Json listed = report::readJsonFile(path("l.json"));
  const report::Json* listing = report::member(listed, "listing");
  ASSERT_NE(listing, nullptr);
  EXPECT_EQ(listing->at("matches").size(), 2u);
  EXPECT_EQ(listing->at("false_positives")[0].at("class").get<std::string>(), "monitor");
  EXPECT_EQ(listing->at("missed")[0].at("index").get<double>(), 1);
  // Placing the estimate 0.4 m back along x makes the car exact.
  ASSERT_EQ(run("slide-eval", "objects " + path("est.txt") + "@-0.4,0,0,0 " + path("gt.txt") + " --json " + path("o2.json")),
            0);
  EXPECT_NEAR(report::readJsonFile(path("o2.json")).at("per_class")[0].at("position_rmse_m").get<double>(), 0.0,
              1e-9);

  ASSERT_EQ(run("slide-eval", "transform --est 1,2,0,10 --truth '1 2 0.5 0 0 0 1' --json " + path("t.json")), 0);
  const report::Json t = report::readJsonFile(path("t.json"));
  EXPECT_NEAR(t.at("translation_m").get<double>(), 0.5, 1e-9);
  EXPECT_NEAR(t.at("yaw_deg").get<double>(), 10, 1e-9);

  std::vector<StampedPose> traj;
  for (int i = 0; i < 20; ++i) traj.push_back({0.1 * i, poseFromXyzYaw(0.5 * i, 0.1 * i, 0, 0)});
  io::writeTum(path("traj.tum"), traj);
  for (const char* out : {"map.png", "map.svg"}) {
    ASSERT_EQ(run("slide-plot", "map --map " + path("est.txt") + " --gt-map " + path("gt.txt") + " --traj " +
                                    path("traj.tum") + " --view oblique -o " + path(out)),
              0)
        << output();
    EXPECT_GT(fs::file_size(path(out)), 1000u);
  }
  ASSERT_EQ(run("slide-plot", "ate " + path("traj.tum") + " " + path("traj.tum") + " -o " + path("ate.svg")), 0) << output();
  EXPECT_GT(fs::file_size(path("ate.svg")), 1000u);
  EXPECT_EQ(run("slide-plot", "map --map " + path("missing.txt") + " -o " + path("x.png")), 1);
  EXPECT_NE(output().find("missing.txt"), std::string::npos);
}
