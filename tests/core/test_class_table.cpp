#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "config/config.h"
#include "objects/class_table.h"

using namespace slide;

namespace {
std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

// Runs f, expecting a ConfigError whose message contains every fragment.
template <typename F>
void expectError(F f, std::initializer_list<const char*> fragments) {
  try {
    f();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    for (const char* frag : fragments) EXPECT_NE(std::string(e.what()).find(frag), std::string::npos) << e.what();
  }
}

const char* kGood = R"(classes:
  - id: 10
    name: car
    shape: cuboid
    association_distance: 3.0
    model_difference: 2.0
    size_min: [2.5, 1.3, 1.0]
    size_max: [6.5, 2.6, 2.8]
    semantickitti: [10, 252]
    map_labels: [-2]
)";
}  // namespace

TEST(ClassTable, LoadsShippedTable) {
  const ClassTable t = ClassTable::loadDefault();
  EXPECT_EQ(t.at(10).name, "car");
  EXPECT_EQ(t.at(10).shape, Shape::Cuboid);
  EXPECT_EQ(t.at(71).shape, Shape::Cylinder);
  EXPECT_EQ(t.at(1).shape, Shape::Ellipsoid);
  EXPECT_EQ(t.fromSemanticKitti(252), 10);
  EXPECT_EQ(t.fromSemanticKitti(80), 80);
  EXPECT_FALSE(t.fromSemanticKitti(40).has_value());  // road is not an object
  EXPECT_EQ(t.fromMapLabel(-1), 71);
  EXPECT_EQ(t.fromMapLabel(3), 3);
  EXPECT_EQ(t.findByName("trunk")->id, 71);
  EXPECT_THROW(t.at(12345), std::out_of_range);
}

// One kind: a class with itself, a family (trunk, pole), and the catch-all "other" with a class
// of its shape (a chair the detector missed is an "other"), not with a car or a trunk; two named
// furniture classes are not. A catch-all detection meets a named landmark under the named
// class's thresholds; every other pair under the detection's.
TEST(ClassTable, TheCatchAllIsOfOneKindWithItsShapesClasses) {
  const ClassTable t = ClassTable::loadDefault();
  EXPECT_EQ(t.fromSemanticKitti(99), 0);
  EXPECT_TRUE(t.at(0).catch_all);
  EXPECT_FALSE(t.at(1).catch_all);
  EXPECT_TRUE(t.sameKind(71, 80));
  EXPECT_TRUE(t.sameKind(0, 1));
  EXPECT_TRUE(t.sameKind(3, 0));
  EXPECT_FALSE(t.sameKind(1, 2));
  EXPECT_FALSE(t.sameKind(0, 10));
  EXPECT_FALSE(t.sameKind(71, 0));
  EXPECT_EQ(t.gateClass(0, 1)->id, 1);
  EXPECT_EQ(t.gateClass(1, 0)->id, 1);
  EXPECT_EQ(t.gateClass(0, 0)->id, 0);
  EXPECT_EQ(t.gateClass(80, 71)->id, 80);
  EXPECT_EQ(t.gateClass(12345, 1), nullptr);
}

TEST(ClassTable, SizePlausibility) {
  const ClassTable t = ClassTable::loadDefault();
  Object o;
  o.class_id = 10;
  o.model = Cuboid{Pose::Identity(), {4.5, 1.8, 1.5}};
  EXPECT_TRUE(t.sizePlausible(o));
  o.model = Cuboid{Pose::Identity(), {12, 1.8, 1.5}};
  EXPECT_FALSE(t.sizePlausible(o));
  o.class_id = 999;
  EXPECT_FALSE(t.sizePlausible(o));
}

TEST(ClassTable, GoodFileLoads) {
  const ClassTable t = ClassTable::load(writeTemp("good.yaml", kGood));
  EXPECT_EQ(t.ids(), std::vector<int>{10});
  // Without size_typical: per axis the geometric mean of size_min and size_max.
  EXPECT_FALSE(t.at(10).size_typical.has_value());
  EXPECT_TRUE(t.at(10).typicalSize().isApprox(Eigen::Vector3d(std::sqrt(2.5 * 6.5), std::sqrt(1.3 * 2.6), std::sqrt(2.8))));
}

TEST(ClassTable, TypicalSizeGivenOrCheckedAgainstTheRange) {
  EXPECT_TRUE(ClassTable::loadDefault().at(10).typicalSize().isApprox(Eigen::Vector3d(4.5, 1.8, 1.5)));
  std::string typical = kGood;
  typical.insert(typical.find("    semantickitti"), "    size_typical: [4.0, 1.7, 1.4]\n");
  EXPECT_TRUE(ClassTable::load(writeTemp("typical.yaml", typical)).at(10).typicalSize().isApprox(Eigen::Vector3d(4.0, 1.7, 1.4)));
  std::string outside = kGood;
  outside.insert(outside.find("    semantickitti"), "    size_typical: [7.0, 1.7, 1.4]\n");
  expectError([&] { ClassTable::load(writeTemp("outside.yaml", outside)); },
              {"classes[0].size_typical", "between size_min and size_max"});
}

TEST(ClassTable, ErrorsNameFileKeyAndExpectation) {
  expectError([] { ClassTable::load("/nonexistent/classes.yaml"); }, {"/nonexistent/classes.yaml", "cannot open"});
  std::string missing = kGood;
  missing.erase(missing.find("    model_difference"), std::string("    model_difference: 2.0\n").size());
  expectError([&] { ClassTable::load(writeTemp("missing.yaml", missing)); },
              {"missing.yaml", "classes[0].model_difference", "missing key"});
  std::string wrong_type = kGood;
  wrong_type.replace(wrong_type.find("3.0"), 3, "far");
  expectError([&] { ClassTable::load(writeTemp("type.yaml", wrong_type)); },
              {"classes[0].association_distance", "expected a number", "'far'", "line 5"});
  std::string bad_shape = kGood;
  bad_shape.replace(bad_shape.find("cuboid"), 6, "box");
  expectError([&] { ClassTable::load(writeTemp("shape.yaml", bad_shape)); },
              {"classes[0].shape", "cuboid, cylinder, ellipsoid", "'box'"});
  std::string bad_value = kGood;
  bad_value.replace(bad_value.find("3.0"), 3, "-1");
  expectError([&] { ClassTable::load(writeTemp("value.yaml", bad_value)); },
              {"association_distance", "must be positive"});
  std::string short_list = kGood;
  short_list.replace(short_list.find("[2.5, 1.3, 1.0]"), 15, "[2.5, 1.3]");
  expectError([&] { ClassTable::load(writeTemp("list.yaml", short_list)); }, {"size_min", "expected 3 values, got 2"});
  expectError([&] { ClassTable::load(writeTemp("dup.yaml", std::string(kGood) + std::string(kGood).substr(9))); },
              {"classes[1]", "duplicate class id 10"});
  expectError([&] { ClassTable::load(writeTemp("syntax.yaml", "classes: [1, 2\n")); }, {"syntax.yaml", "syntax error", "line"});
}

TEST(Config, OptionalAndNested) {
  const ConfigNode c = ConfigNode::parse("a: 1\nb:\n  c: [1, 2]\n  d: yes\n", "inline");
  EXPECT_EQ(c.get<int>("a"), 1);
  EXPECT_EQ(c.get<double>("zz", 2.5), 2.5);
  EXPECT_EQ(c.child("b").getList<int>("c"), (std::vector<int>{1, 2}));
  EXPECT_TRUE(c.child("b").get<bool>("d"));
  expectError([&] { c.child("b").get<int>("d"); }, {"inline: b.d: expected an integer"});
  expectError([&] { c.child("a"); }, {"inline: a: expected a map or a list"});
}

TEST(Config, ReadKeepsDefaultsAndChecksSigns) {
  const ConfigNode c = ConfigNode::parse("rate: 2.5\ncount: 7\nneg: -1\nzero: 0\n", "inline");
  double rate = 1.0, missing = 4.0;
  std::size_t count = 0;
  c.read("rate", rate);
  c.read("missing", missing);
  c.read("count", count);
  EXPECT_EQ(rate, 2.5);
  EXPECT_EQ(missing, 4.0);
  EXPECT_EQ(count, 7u);
  std::size_t unsigned_value = 3;
  expectError([&] { c.read("neg", unsigned_value); }, {"inline: neg: expected a non-negative integer, got '-1'"});
  EXPECT_EQ(unsigned_value, 3u);
  c.requirePositive("rate", rate);
  expectError([&] { c.requirePositive("zero", 0.0); }, {"inline: zero: must be positive"});
  c.requireNonNegative("zero", 0.0);
  expectError([&] { c.requireNonNegative("neg", -1.0); }, {"inline: neg: must not be negative"});
}
