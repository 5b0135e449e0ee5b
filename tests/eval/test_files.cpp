#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "eval/object_map_file.h"
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
  ClassTable classes_ = ClassTable::loadDefault();
};
}  // namespace

TEST_F(Files, TextMapWithLabelsClassIdsAndSizes) {
  const auto p = write("map.txt", "# comment\n-2 1 2 0.5\n-1 3 4 2\n71 5 6 1 0.4 0.4 8\n10 0 0 1 4 2 1.5 0.5\n0 1 1 1\n");
  const auto objs = readObjectMapFile(p, classes_);
  ASSERT_EQ(objs.size(), 5u);
  EXPECT_EQ(objs[0].class_id, 10);  // map label -2 = car
  EXPECT_EQ(objs[0].shape(), Shape::Cuboid);
  EXPECT_TRUE(objs[0].position().isApprox(Eigen::Vector3d(1, 2, 0.5)));
  EXPECT_EQ(objs[1].class_id, 71);  // map label -1 = trunk
  EXPECT_EQ(objs[1].shape(), Shape::Cylinder);
  EXPECT_TRUE(objs[1].position().isApprox(Eigen::Vector3d(3, 4, 2)));
  EXPECT_EQ(objs[2].class_id, 71);  // class id 71
  EXPECT_NEAR(std::get<Cylinder>(objs[2].model).radius, 0.2, 1e-12);
  EXPECT_NEAR(std::get<Cylinder>(objs[2].model).length, 8, 1e-12);
  EXPECT_TRUE(objs[3].extent().isApprox(Eigen::Vector3d(4, 2, 1.5)));
  EXPECT_NEAR(yawOf(std::get<Cuboid>(objs[3].model).pose.linear()), 0.5, 1e-12);
  EXPECT_EQ(objs[4].class_id, 0);
}

TEST_F(Files, RealRobotMapsLoad) {
  const auto parking = readObjectMapFile(std::string(SLIDE_DATA_DIR) + "/slideslam_maps/parking/robot0.txt", classes_);
  EXPECT_EQ(parking.size(), 142u);
  const auto indoor = readObjectMapFile(std::string(SLIDE_DATA_DIR) + "/slideslam_maps/indoor/robot1.txt", classes_);
  EXPECT_EQ(indoor.size(), 35u);
}

TEST_F(Files, CsvRoundTripAndHeaderAliases) {
  const auto txt = write("m.txt", "-2 1 2 0.5 4 2 1.5 0.3\n-1 3 4 2 0.5 0.5 6\n3 0 0 1\n");
  const auto objs = readObjectMapFile(txt, classes_);
  const std::string csv = (dir_ / "m.csv").string();
  writeObjectMapCsv(csv, objs);
  const auto back = readObjectMapFile(csv, classes_);
  ASSERT_EQ(back.size(), objs.size());
  for (std::size_t i = 0; i < objs.size(); ++i) {
    EXPECT_EQ(back[i].class_id, objs[i].class_id);
    EXPECT_EQ(back[i].shape(), objs[i].shape());
    EXPECT_TRUE(back[i].position().isApprox(objs[i].position(), 1e-9));
    EXPECT_TRUE(back[i].extent().isApprox(objs[i].extent(), 1e-9));
  }
  // A leaning trunk keeps its axis.
  Object lean;
  lean.class_id = 71;
  lean.model = Cylinder{{1, 2, 0}, Eigen::Vector3d(0, 0.6, 0.8), 0.25, 5};
  writeObjectMapCsv(csv, {lean});
  const auto l = readObjectMapFile(csv, classes_);
  EXPECT_TRUE(std::get<Cylinder>(l[0].model).axis.isApprox(Eigen::Vector3d(0, 0.6, 0.8), 1e-9));
  EXPECT_TRUE(std::get<Cylinder>(l[0].model).root.isApprox(Eigen::Vector3d(1, 2, 0), 1e-9));
  // Columns in another order, a radius column, an extra column.
  const auto other = write("o.csv", "x,y,z,class,radius,height,note\n1,2,3,71,0.3,5,hello\n");
  const auto o = readObjectMapFile(other, classes_);
  ASSERT_EQ(o.size(), 1u);
  EXPECT_NEAR(std::get<Cylinder>(o[0].model).radius, 0.3, 1e-12);
  EXPECT_TRUE(o[0].position().isApprox(Eigen::Vector3d(1, 2, 3)));
}

TEST_F(Files, SimulatorGroundTruthCsv) {
  // The layout of the simulator's objects.csv (sim branch, io/ground_truth_objects.h).
  const auto p = write("objects.csv",
                       "id,class_id,shape,x,y,z,yaw,length,width,height,radius,axis_x,axis_y,axis_z,semantic,vx,vy\n"
                       "1,10,cuboid,5,2,0.8,0.5,4.2,1.8,1.6,0,0,0,1,10,0,0\n"
                       "2,71,cylinder,1,1,3,0,0.6,0.6,6,0.3,0.6,0,0.8,71,0,0\n"
                       "3,2,ellipsoid,0,4,0.4,0,1.2,1.2,0.8,0.6,0,0,1,0,0,0\n");
  const auto objs = readObjectMapFile(p, classes_);
  ASSERT_EQ(objs.size(), 3u);
  EXPECT_EQ(objs[0].id, 1);
  EXPECT_TRUE(objs[0].extent().isApprox(Eigen::Vector3d(4.2, 1.8, 1.6)));
  EXPECT_NEAR(yawOf(std::get<Cuboid>(objs[0].model).pose.linear()), 0.5, 1e-12);
  const Cylinder& c = std::get<Cylinder>(objs[1].model);
  EXPECT_NEAR(c.radius, 0.3, 1e-12);
  EXPECT_TRUE(c.axis.isApprox(Eigen::Vector3d(0.6, 0, 0.8)));
  EXPECT_TRUE(objs[1].position().isApprox(Eigen::Vector3d(1, 1, 3)));
  EXPECT_NEAR(std::get<Ellipsoid>(objs[2].model).radius, 0.6, 1e-12);
  EXPECT_NEAR(std::get<Ellipsoid>(objs[2].model).height, 0.8, 1e-12);
}

TEST_F(Files, PoleListWithDefaultClass) {
  const auto p = std::string(SLIDE_DATA_DIR) + "/kitti/poles/05.csv";
  EXPECT_THROW(readObjectMapFile(p, classes_), IoError);
  const auto poles = readObjectMapFile(p, classes_, 80);
  EXPECT_EQ(poles.size(), 321u);
  EXPECT_EQ(poles[0].class_id, 80);
  EXPECT_NEAR(poles[0].position().x(), 32.4410, 1e-9);
  EXPECT_NEAR(poles[0].position().z(), 0.0, 1e-9);
}

TEST_F(Files, BadMapsNameFileAndLine) {
  auto expectError = [&](const std::string& name, const std::string& text, const std::string& needle) {
    const auto p = write(name, text);
    try {
      readObjectMapFile(p, classes_);
      ADD_FAILURE() << "no error for " << name;
    } catch (const IoError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(p), std::string::npos) << m;
      EXPECT_NE(m.find(needle), std::string::npos) << m;
    }
  };
  expectError("a.txt", "1 2 3 4\n1 2 x 4\n", "line 2");
  expectError("b.txt", "999 0 0 0\n", "label 999");
  expectError("c.txt", "1 2 3\n", "label x y z");
  expectError("d.csv", "id,x,y\n1,2,3\n", "class_id");
  expectError("d2.csv", "id,x\n1,2\n", "class_id, x, y");
  expectError("e.csv", "class_id,x,y,z,shape\n10,1,2,3,cube\n", "shape");
  expectError("f.csv", "class_id,x,y,z\n10,1,2\n", "missing field z");
  EXPECT_THROW(readObjectMapFile((dir_ / "none.txt").string(), classes_), IoError);
}

TEST_F(Files, TrajectoryFormatsAreDetected) {
  const auto tum = write("t.txt", "# t x y z qx qy qz qw\n0.5 1 2 3 0 0 0 1\n1.5 2 2 3 0 0 0 1\n");
  const auto a = readTrajectory(tum);
  ASSERT_EQ(a.size(), 2u);
  EXPECT_DOUBLE_EQ(a[1].t, 1.5);
  const std::string kitti = (dir_ / "k.txt").string();
  writeKittiPoses(kitti, {poseFromXyzYaw(1, 0, 0, 0), poseFromXyzYaw(2, 0, 0, 0), poseFromXyzYaw(3, 0, 0, 0)});
  const auto k = readTrajectory(kitti);
  ASSERT_EQ(k.size(), 3u);
  EXPECT_DOUBLE_EQ(k[2].t, 2.0);
  EXPECT_DOUBLE_EQ(k[2].pose.translation().x(), 3.0);
  const auto times = write("times.txt", "0.0\n0.1\n0.2\n");
  EXPECT_DOUBLE_EQ(readTrajectory(kitti, TrajectoryFormat::Kitti, times)[1].t, 0.1);
  const auto short_times = write("short.txt", "0.0\n");
  EXPECT_THROW(readTrajectory(kitti, TrajectoryFormat::Auto, short_times), IoError);
  EXPECT_THROW(readTrajectory(write("bad.txt", "1 2 3\n")), IoError);
  EXPECT_THROW(parseTrajectoryFormat("evo"), std::invalid_argument);
}

TEST_F(Files, StageSamples) {
  const auto p = write("s.txt", "# timings\nfit 2.0\nfit 4.0\nupdate 1.5\n");
  const auto s = readStageSamples(p);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.at("fit").size(), 2u);
  EXPECT_THROW(readStageSamples(write("bad_s.txt", "fit two\n")), IoError);
  EXPECT_EQ(readStageSamples(write("plain.txt", "1\n2\n")).at("all").size(), 2u);
}
