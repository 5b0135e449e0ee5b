#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "io/ground_truth_objects.h"
#include "io/io_error.h"
#include "io/object_map_text.h"

using namespace slide;

TEST(ObjectMapText, ReadsTheRealParkingAndIndoorMaps) {
  const ClassTable classes = ClassTable::loadDefault();
  const io::ObjectMapText parking = io::readObjectMapText(
      std::string(SLIDE_DATA_DIR) + "/slideslam_maps/parking/robot0.txt", classes, io::MissingSize::Zero);
  EXPECT_EQ(parking.map.size(), 142u);
  int cars = 0, trunks = 0, other = 0;
  for (const Object& o : parking.map.objects()) {
    cars += o.class_id == 10 && o.shape() == Shape::Cuboid;
    trunks += o.class_id == 71 && o.shape() == Shape::Cylinder;
    other += o.class_id == 0;
  }
  EXPECT_EQ(cars, 82);
  EXPECT_EQ(trunks, 34);
  EXPECT_EQ(other, 26);
  EXPECT_NEAR(parking.map[0].position().x(), -9.81972, 1e-9);
  const io::ObjectMapText indoor = io::readObjectMapText(
      std::string(SLIDE_DATA_DIR) + "/slideslam_maps/indoor/robot1.txt", classes, io::MissingSize::Zero);
  EXPECT_EQ(indoor.map.size(), 35u);
  EXPECT_EQ(indoor.map[0].shape(), Shape::Ellipsoid);
}

TEST(ObjectMapText, RoundTripKeepsClassPositionAndSize) {
  const ClassTable classes = ClassTable::loadDefault();
  const io::ObjectMapText in =
      io::parseObjectMapText("-2 1 2 3 4.5 1.8 1.5\n# comment\n\n-1 5 6 7 0.4 0.4 3\n1 0 0 0\n80 1 1 1 0.2 0.2 5\n",
                             "mem", classes, io::MissingSize::Zero);
  ASSERT_EQ(in.map.size(), 4u);
  const io::ObjectMapText out =
      io::parseObjectMapText(io::formatObjectMapText(in.map, classes), "again", classes, io::MissingSize::Zero);
  ASSERT_EQ(out.map.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(out.map[i].class_id, in.map[i].class_id);
    EXPECT_NEAR((out.map[i].position() - in.map[i].position()).norm(), 0, 1e-6);
    EXPECT_NEAR((out.map[i].extent() - in.map[i].extent()).norm(), 0, 1e-6);
  }
  EXPECT_EQ(out.map[1].class_id, 71);
  EXPECT_NEAR(out.map[1].extent().x(), 0.4, 1e-9);
  EXPECT_EQ(out.map[3].class_id, 80);
}

TEST(ObjectMapText, ErrorsNameFileAndLine) {
  const ClassTable classes = ClassTable::loadDefault();
  auto message = [&](const std::string& text) {
    try {
      io::parseObjectMapText(text, "m.txt", classes, io::MissingSize::Zero);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("1 0 0 0\n1 2 x 3\n"), "m.txt: line 2: field 3 is not a number: 'x'");
  EXPECT_EQ(message("1 0 0\n"), "m.txt: line 1: expected 'label x y z [sx sy sz [yaw]]', got 3 fields");
  EXPECT_NE(message("99 0 0 0\n").find("m.txt: line 1: label 99"), std::string::npos);
  EXPECT_EQ(message("1 0 0 0 1 -1 1\n"), "m.txt: line 1: negative size");
  EXPECT_NE(message("1.5 0 0 0\n").find("integer class label"), std::string::npos);
  EXPECT_THROW(io::readObjectMapText("/nonexistent/map.txt", classes, io::MissingSize::Zero), io::IoError);
  const io::ObjectMapText nan = io::parseObjectMapText("1 nan 0 0\n1 1 1 1\n", "n.txt", classes, io::MissingSize::Zero);
  EXPECT_EQ(nan.map.size(), 1u);
  ASSERT_EQ(nan.warnings.size(), 1u);
  EXPECT_EQ(nan.warnings[0], "n.txt: line 1: non-finite number, object skipped");
}

TEST(ObjectMapText, MissingSizesFollowTheReadersPolicy) {
  const ClassTable classes = ClassTable::loadDefault();
  const std::string text = "-2 1 2 0.5\n-2 1 2 0.5 4 2 1.5\n";
  const io::ObjectMapText zero = io::parseObjectMapText(text, "z.txt", classes, io::MissingSize::Zero);
  const io::ObjectMapText typical = io::parseObjectMapText(text, "t.txt", classes, io::MissingSize::ClassTypical);
  ASSERT_EQ(zero.map.size(), 2u);
  ASSERT_EQ(typical.map.size(), 2u);
  EXPECT_TRUE(zero.map[0].extent().isZero());
  EXPECT_TRUE(typical.map[0].extent().isApprox(classes.at(10).typicalSize()));
  EXPECT_FALSE(typical.map[0].extent().isZero());
  // Given sizes are the same under either policy.
  EXPECT_TRUE(zero.map[1].extent().isApprox(Eigen::Vector3d(4, 2, 1.5)));
  EXPECT_TRUE(typical.map[1].extent().isApprox(Eigen::Vector3d(4, 2, 1.5)));
}

TEST(ObjectMapText, DirectoryAndOutOfRangeLabelAreErrorsNamingThem) {
  const ClassTable classes = ClassTable::loadDefault();
  const std::string dir = ::testing::TempDir() + "slide_map_dir";
  std::filesystem::create_directories(dir);
  try {
    io::readObjectMapText(dir, classes, io::MissingSize::Zero);
    FAIL() << "a directory was read as an empty map";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), dir + ": is a directory, not an object map file");
  }
  for (const char* label : {"1e20", "-1e20", "2147483648"}) {
    try {
      io::parseObjectMapText(std::string("1 0 0 0\n") + label + " 1 2 3\n", "big.txt", classes, io::MissingSize::Zero);
      ADD_FAILURE() << "label " << label << " was accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), std::string("big.txt: line 2: class label '") + label + "' is out of the integer range");
    }
  }
}

namespace {
class ObjectMapFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("slide_object_map_file_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const std::string p = (dir_ / name).string();
    std::ofstream(p) << text;
    return p;
  }
  std::filesystem::path dir_;
  ClassTable classes_ = ClassTable::loadDefault();
};
}  // namespace

TEST_F(ObjectMapFile, TextMapWithLabelsClassIdsAndSizes) {
  const auto p = write("map.txt", "# comment\n-2 1 2 0.5\n-1 3 4 2\n71 5 6 1 0.4 0.4 8\n10 0 0 1 4 2 1.5 0.5\n0 1 1 1\n");
  const auto objs = io::readObjectMapFile(p, classes_);
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

TEST_F(ObjectMapFile, RealRobotMapsLoad) {
  const auto parking =
      io::readObjectMapFile(std::string(SLIDE_DATA_DIR) + "/slideslam_maps/parking/robot0.txt", classes_);
  EXPECT_EQ(parking.size(), 142u);
  const auto indoor =
      io::readObjectMapFile(std::string(SLIDE_DATA_DIR) + "/slideslam_maps/indoor/robot1.txt", classes_);
  EXPECT_EQ(indoor.size(), 35u);
}

TEST_F(ObjectMapFile, CsvRoundTripAndHeaderAliases) {
  const auto txt = write("m.txt", "-2 1 2 0.5 4 2 1.5 0.3\n-1 3 4 2 0.5 0.5 6\n3 0 0 1\n");
  const auto objs = io::readObjectMapFile(txt, classes_);
  const std::string csv = (dir_ / "m.csv").string();
  std::vector<io::GroundTruthObject> rows(objs.size());
  for (std::size_t i = 0; i < objs.size(); ++i) rows[i].object = objs[i];
  io::writeGroundTruthObjects(csv, rows);
  const auto back = io::readObjectMapFile(csv, classes_);
  ASSERT_EQ(back.size(), objs.size());
  for (std::size_t i = 0; i < objs.size(); ++i) {
    EXPECT_EQ(back[i].class_id, objs[i].class_id);
    EXPECT_EQ(back[i].shape(), objs[i].shape());
    EXPECT_TRUE(back[i].position().isApprox(objs[i].position(), 1e-6));
    EXPECT_TRUE(back[i].extent().isApprox(objs[i].extent(), 1e-6));
  }
  // A leaning trunk keeps its axis.
  io::GroundTruthObject lean;
  lean.object.class_id = 71;
  lean.object.model = Cylinder{{1, 2, 0}, Eigen::Vector3d(0, 0.6, 0.8), 0.25, 5};
  io::writeGroundTruthObjects(csv, {lean});
  const auto l = io::readObjectMapFile(csv, classes_);
  EXPECT_TRUE(std::get<Cylinder>(l[0].model).axis.isApprox(Eigen::Vector3d(0, 0.6, 0.8), 1e-6));
  EXPECT_TRUE(std::get<Cylinder>(l[0].model).root.isApprox(Eigen::Vector3d(1, 2, 0), 1e-6));
  // Columns in another order, a radius column, an extra column.
  const auto other = write("o.csv", "x,y,z,class,radius,height,note\n1,2,3,71,0.3,5,hello\n");
  const auto o = io::readObjectMapFile(other, classes_);
  ASSERT_EQ(o.size(), 1u);
  EXPECT_NEAR(std::get<Cylinder>(o[0].model).radius, 0.3, 1e-12);
  EXPECT_TRUE(o[0].position().isApprox(Eigen::Vector3d(1, 2, 3)));
}

TEST_F(ObjectMapFile, SimulatorGroundTruthCsv) {
  // The layout of the simulator's objects.csv (sim branch, io/ground_truth_objects.h).
  const auto p = write("objects.csv",
                       "id,class_id,shape,x,y,z,yaw,length,width,height,radius,axis_x,axis_y,axis_z,semantic,vx,vy\n"
                       "1,10,cuboid,5,2,0.8,0.5,4.2,1.8,1.6,0,0,0,1,10,0,0\n"
                       "2,71,cylinder,1,1,3,0,0.6,0.6,6,0.3,0.6,0,0.8,71,0,0\n"
                       "3,2,ellipsoid,0,4,0.4,0,1.2,1.2,0.8,0.6,0,0,1,0,0,0\n");
  const auto objs = io::readObjectMapFile(p, classes_);
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

TEST_F(ObjectMapFile, PoleListWithDefaultClass) {
  const auto p = std::string(SLIDE_DATA_DIR) + "/kitti/poles/05.csv";
  EXPECT_THROW(io::readObjectMapFile(p, classes_), io::IoError);
  const auto poles = io::readObjectMapFile(p, classes_, 80);
  EXPECT_EQ(poles.size(), 321u);
  EXPECT_EQ(poles[0].class_id, 80);
  EXPECT_NEAR(poles[0].position().x(), 32.4410, 1e-9);
  EXPECT_NEAR(poles[0].position().z(), 0.0, 1e-9);
}

TEST_F(ObjectMapFile, BadMapsNameFileAndLine) {
  auto expectError = [&](const std::string& name, const std::string& text, const std::string& needle) {
    const auto p = write(name, text);
    try {
      io::readObjectMapFile(p, classes_);
      ADD_FAILURE() << "no error for " << name;
    } catch (const io::IoError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(p), std::string::npos) << m;
      EXPECT_NE(m.find(needle), std::string::npos) << m;
    }
  };
  expectError("a.txt", "1 2 3 4\n1 2 x 4\n", "line 2");
  expectError("b.txt", "999 0 0 0\n", "label 999");
  expectError("c.txt", "1 2 3\n", "label x y z");
  expectError("c2.txt", "1 2 3 nan\n", "non-finite");
  expectError("d.csv", "id,x,y\n1,2,3\n", "class_id");
  expectError("d2.csv", "id,x\n1,2\n", "class_id, x, y");
  expectError("e.csv", "class_id,x,y,z,shape\n10,1,2,3,cube\n", "shape");
  expectError("f.csv", "class_id,x,y,z\n10,1,2\n", "missing field z");
  EXPECT_THROW(io::readObjectMapFile((dir_ / "none.txt").string(), classes_), io::IoError);
}
