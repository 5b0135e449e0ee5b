// Misspelled configuration keys are errors naming file, key path, line and the nearest known
// key; keys of sections another reader owns, and data maps read key by key, are not.
#include <gtest/gtest.h>

#include <fstream>

#include "config/config.h"
#include "objects/class_table.h"

using namespace slide;

namespace {
std::string rejected(const ConfigNode& n) {
  try {
    n.rejectUnknownKeys();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(ConfigKeys, MisspelledKeyNamesFileKeyLineAndNearestKnownKey) {
  const ConfigNode c = ConfigNode::parse("rate: 2\nodometry:\n  max_step: 3\n  floor: 1\n", "robot.yaml");
  double rate = 0, step = 0, floor = 0;
  c.read("rate", rate);
  const ConfigNode o = c.child("odometry");
  o.read("max_step_m", step);
  o.read("max_step_rad", step);
  o.read("floor", floor);
  EXPECT_EQ(step, 0.0);  // the misspelled value was not taken
  const std::string e = rejected(c);
  EXPECT_NE(e.find("robot.yaml: odometry.max_step (line 3): unknown key; did you mean 'max_step_m'?"), std::string::npos)
      << e;
  EXPECT_EQ(c.unknownKeys().size(), 1u);
}

TEST(ConfigKeys, UnreadTopLevelSectionIsUnknownToTheFileOwner) {
  const ConfigNode c = ConfigNode::parse("odometry:\n  a: 1\nodometyr:\n  a: 2\n", "b.yaml");
  if (c.has("odometry")) c.child("odometry").get<int>("a");
  const std::string e = rejected(c);
  EXPECT_NE(e.find("b.yaml: odometyr (line 3): unknown key; did you mean 'odometry'?"), std::string::npos) << e;
}

TEST(ConfigKeys, KnownKeysPassAndSectionOwnersJudgeOnlyTheirSection) {
  // One shared file, two readers: each rejects unknown keys in its own section only.
  const std::string text = "sensor_driver:\n  rate: 1\npeer_sync:\n  team: [0, 1]\n  tick_perod_s: 1\n";
  const ConfigNode a = ConfigNode::parse(text, "shared.yaml");
  const ConfigNode driver = a.child("sensor_driver");
  driver.get<double>("rate", 0.0);
  EXPECT_EQ(rejected(driver), "");
  const ConfigNode b = ConfigNode::parse(text, "shared.yaml");
  const ConfigNode sync = b.child("peer_sync");
  sync.getList<int>("team");
  sync.get<double>("tick_period_s", 0.05);
  const std::string e = rejected(sync);
  EXPECT_NE(e.find("shared.yaml: peer_sync.tick_perod_s (line 5): unknown key; did you mean 'tick_period_s'?"),
            std::string::npos)
      << e;
}

TEST(ConfigKeys, ListElementsAndDataMapsReadKeyByKey) {
  const ConfigNode c =
      ConfigNode::parse("items:\n  - {id: 1, confusion: {20: 0.1}}\n  - {id: 2, colour: [1, 2, 3]}\n", "l.yaml");
  const ConfigNode items = c.child("items");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const ConfigNode it = items[i];
    it.get<int>("id");
    it.has("color");
    if (it.has("confusion"))
      for (const std::string& k : it.child("confusion").keys()) it.child("confusion").get<double>(k);
  }
  const std::vector<std::string> u = c.unknownKeys();
  ASSERT_EQ(u.size(), 1u);
  EXPECT_EQ(u[0], "l.yaml: items[1].colour (line 3): unknown key; did you mean 'color'?");
}

TEST(ConfigKeys, ClassTableRejectsAMisspelledClassKey) {
  const std::string path = testing::TempDir() + "misspelled_classes.yaml";
  std::ofstream(path) << "classes:\n  - id: 1\n    name: car\n    shape: cuboid\n    association_distance: 1\n"
                         "    model_difference: 1\n    size_min: [1, 1, 1]\n    size_max: [5, 5, 5]\n"
                         "    map_lables: [7]\n";
  try {
    ClassTable::load(path);
    FAIL() << "a misspelled key was ignored";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": classes[0].map_lables (line 9): unknown key; did you mean "
                                                "'map_labels'?"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(ClassTable::loadDefault());
}

TEST(ConfigKeys, KeysOverriddenOnTheCommandLineStayKnown) {
  const ConfigNode c = ConfigNode::parse("rate: 2\nstate_dir: /x\nstate_dri: /y\n", "d.yaml");
  c.get<double>("rate", 1.0);
  c.known({"state_dir"});  // --state-dir given: the reader skips the key but knows it
  const std::vector<std::string> u = c.unknownKeys();
  ASSERT_EQ(u.size(), 1u);
  EXPECT_EQ(u[0], "d.yaml: state_dri (line 3): unknown key; did you mean 'state_dir'?");
}
