// A short indoor drive mapped by LiDAR and by RGBD: both give objects, in the robot's own
// frame, that lie on true objects of their class.
#include <gtest/gtest.h>

#include "mapped_robot/map_robot.h"

using namespace slide;

namespace {
int nearTrue(const std::vector<Object>& map, const Pose& T_world_odom, const simulator::World& world) {
  int n = 0;
  for (const Object& o : map) {
    const Eigen::Vector3d p = T_world_odom * o.position();
    for (const auto& g : world.objects)
      if (g.object.class_id == o.class_id && (g.object.position() - p).head<2>().norm() < 0.5) {
        ++n;
        break;
      }
  }
  return n;
}

mapped_robot::MappingSetup setup() {
  return {ClassTable::loadDefault(), frontend::loadDefaultFrontendConfig(),
          backend::loadBackendConfig(std::string(SLIDE_SOURCE_DIR) + "/config/backend.yaml"), 3,
          std::nullopt};  // ground-truth labels
}
}  // namespace

TEST(MapRobot, LidarAndRgbdMapsLieOnTrueObjects) {
  simulator::ScenarioSpec spec;
  spec.world = "indoor";
  spec.robots = 1;
  spec.distance = 16;
  spec.rate = 2;
  spec.seed = 2;
  const simulator::Scenario sc = simulator::buildScenario(spec);
  const mapped_robot::MappingSetup s = setup();
  for (const char* sensor : {"lidar:vlp-16", "rgbd:d455"}) {
    const mapped_robot::RobotMapping m = mapped_robot::mapRobot(sc, 0, mapped_robot::parseSensorRig(sensor), s);
    EXPECT_EQ(m.frames, static_cast<int>(sc.robots[0].ground_truth.size())) << sensor;
    EXPECT_GE(m.keyposes, 5) << sensor;
    EXPECT_GT(m.raw_points, 0) << sensor;
    ASSERT_GE(m.objects.size(), 2u) << sensor;
    EXPECT_GE(nearTrue(m.objects, sc.robots[0].T_world_odom, sc.world), static_cast<int>(0.8 * m.objects.size()))
        << sensor;
  }
  EXPECT_THROW(mapped_robot::mapRobot(sc, 1, mapped_robot::parseSensorRig("lidar:vlp-16"), s), std::out_of_range);
}
