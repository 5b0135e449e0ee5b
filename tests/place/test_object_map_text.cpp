#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "mapio/object_map_text.h"

using namespace slide;

TEST(ObjectMapText, ReadsTheRealParkingAndIndoorMaps) {
  const ClassTable classes = ClassTable::loadDefault();
  const ObjectMapText parking = readObjectMapText(std::string(SLIDE_DATA_DIR) + "/slideslam_maps/parking/robot0.txt", classes);
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
  const ObjectMapText indoor = readObjectMapText(std::string(SLIDE_DATA_DIR) + "/slideslam_maps/indoor/robot1.txt", classes);
  EXPECT_EQ(indoor.map.size(), 35u);
  EXPECT_EQ(indoor.map[0].shape(), Shape::Ellipsoid);
}

TEST(ObjectMapText, RoundTripKeepsClassPositionAndSize) {
  const ClassTable classes = ClassTable::loadDefault();
  const ObjectMapText in = parseObjectMapText("-2 1 2 3 4.5 1.8 1.5\n# comment\n\n-1 5 6 7 0.4 0.4 3\n1 0 0 0\n80 1 1 1 0.2 0.2 5\n",
                                              "mem", classes);
  ASSERT_EQ(in.map.size(), 4u);
  const ObjectMapText out = parseObjectMapText(formatObjectMapText(in.map, classes), "again", classes);
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
      parseObjectMapText(text, "m.txt", classes);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("1 0 0 0\n1 2 x 3\n"), "m.txt:2: field 3 is not a number: 'x'");
  EXPECT_EQ(message("1 0 0\n"), "m.txt:1: expected 'label x y z' or 'label x y z sx sy sz', got 3 fields");
  EXPECT_NE(message("99 0 0 0\n").find("m.txt:1: label 99"), std::string::npos);
  EXPECT_NE(message("1.5 0 0 0\n").find("integer class label"), std::string::npos);
  EXPECT_THROW(readObjectMapText("/nonexistent/map.txt", classes), std::runtime_error);
  const ObjectMapText nan = parseObjectMapText("1 nan 0 0\n1 1 1 1\n", "n.txt", classes);
  EXPECT_EQ(nan.map.size(), 1u);
  ASSERT_EQ(nan.warnings.size(), 1u);
  EXPECT_EQ(nan.warnings[0], "n.txt:1: non-finite number, object skipped");
}

TEST(ObjectMapText, DirectoryAndOutOfRangeLabelAreErrorsNamingThem) {
  const ClassTable classes = ClassTable::loadDefault();
  const std::string dir = ::testing::TempDir() + "slide_map_dir";
  std::filesystem::create_directories(dir);
  try {
    readObjectMapText(dir, classes);
    FAIL() << "a directory was read as an empty map";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), dir + ": is a directory, not an object map file");
  }
  for (const char* label : {"1e20", "-1e20", "2147483648"}) {
    try {
      parseObjectMapText(std::string("1 0 0 0\n") + label + " 1 2 3\n", "big.txt", classes);
      ADD_FAILURE() << "label " << label << " was accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), std::string("big.txt:2: class label '") + label + "' is out of the integer range");
    }
  }
}
