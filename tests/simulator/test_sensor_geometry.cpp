// Sensor geometry: rays hit known shapes at known ranges; LiDAR points and depth pixels land
// on the objects their labels name.
#include <gtest/gtest.h>

#include <cmath>

#include "simulator/lidar.h"
#include "simulator/ray_shapes.h"
#include "simulator/rgbd_camera.h"

using namespace slide;

namespace {
// Flat ground at z = 0, one upright cylinder (trunk) centred at (10, 0) with radius 0.5 and
// one car-sized box centred at (0, 8).
simulator::World twoObjectWorld() {
  simulator::World w;
  w.name = "test";
  io::GroundTruthObject trunk;
  trunk.object.class_id = 71;
  trunk.semantic = simulator::label::kTrunk;
  trunk.object.model = Cylinder{{10, 0, 0}, Eigen::Vector3d::UnitZ(), 0.5, 6.0};
  io::GroundTruthObject car;
  car.object.class_id = 10;
  car.semantic = simulator::label::kCar;
  car.object.model = Cuboid{poseFromXyzYaw(0, 8, 0.75, 0), {4.0, 2.0, 1.5}};
  w.objects = {trunk, car};
  w.renumber();
  return w;
}
}  // namespace

TEST(RayShapes, CylinderBoxEllipsoidRanges) {
  const Eigen::Vector3d o(0, 0, 1), x = Eigen::Vector3d::UnitX();
  EXPECT_NEAR(simulator::intersectRayCylinder(o, x, {10, 0, 0}, Eigen::Vector3d::UnitZ(), 0.5, 6.0), 9.5, 1e-9);
  // Misses: above the top, beside it, behind the origin.
  EXPECT_TRUE(
      std::isinf(simulator::intersectRayCylinder({0, 0, 7}, x, {10, 0, 0}, Eigen::Vector3d::UnitZ(), 0.5, 6.0)));
  EXPECT_TRUE(
      std::isinf(simulator::intersectRayCylinder({0, 0.6, 1}, x, {10, 0, 0}, Eigen::Vector3d::UnitZ(), 0.5, 6.0)));
  EXPECT_TRUE(std::isinf(simulator::intersectRayCylinder(o, -x, {10, 0, 0}, Eigen::Vector3d::UnitZ(), 0.5, 6.0)));
  // Leaning cylinder seen from above hits its top cap.
  EXPECT_NEAR(simulator::intersectRayCylinder({10, 0, 10}, -Eigen::Vector3d::UnitZ(), {10, 0, 0},
                                              Eigen::Vector3d::UnitZ(), 0.5, 6.0),
              4.0, 1e-9);
  // Box rotated by 90 degrees: its 4 m length now lies along y.
  const Eigen::Matrix3d R = rotZ(M_PI / 2).transpose();
  EXPECT_NEAR(simulator::intersectRayBox({0, -10, 1}, Eigen::Vector3d::UnitY(), R, {0, 0, 1}, {2, 1, 1}), 8.0, 1e-9);
  EXPECT_NEAR(simulator::intersectRayEllipsoid({-5, 0, 0}, x, {0, 0, 0}, {1, 1, 2}), 4.0, 1e-9);
  EXPECT_NEAR(simulator::intersectRayEllipsoid({0, 0, 5}, -Eigen::Vector3d::UnitZ(), {0, 0, 0}, {1, 1, 2}), 3.0, 1e-9);
}

TEST(RayCaster, HitsNearestLabelledSurface) {
  const simulator::World w = twoObjectWorld();
  const simulator::RayCaster caster(w);
  simulator::RayHit hit;
  ASSERT_TRUE(caster.cast({0, 0, 1}, Eigen::Vector3d::UnitX(), 100, &hit));
  EXPECT_NEAR(hit.range, 9.5, 1e-9);
  EXPECT_EQ(hit.semantic, simulator::label::kTrunk);
  EXPECT_EQ(hit.instance, 1);
  ASSERT_TRUE(caster.cast({0, 0, 1}, Eigen::Vector3d::UnitY(), 100, &hit));
  EXPECT_NEAR(hit.range, 7.0, 1e-9);
  EXPECT_EQ(hit.instance, 2);
  // Down at 45 degrees from 1 m: the ground at sqrt(2) m.
  ASSERT_TRUE(caster.cast({0, 0, 1}, Eigen::Vector3d(1, -1, -std::sqrt(2.0)).normalized(), 100, &hit));
  EXPECT_NEAR(hit.range, std::sqrt(2.0), 1e-6);
  EXPECT_EQ(hit.instance, 0);
  EXPECT_EQ(hit.semantic, simulator::label::kTerrain);
  // Up into the empty sky: nothing.
  EXPECT_FALSE(caster.cast({0, 0, 1}, Eigen::Vector3d(-1, 0, 1).normalized(), 100, &hit));
  // Beyond max range: nothing.
  EXPECT_FALSE(caster.cast({0, 0, 1}, Eigen::Vector3d::UnitX(), 9.0, &hit));
}

TEST(RayCaster, UnevenGroundAgreesWithHeightField) {
  simulator::World w;
  w.terrain = simulator::unevenTerrain(1.0, 3);
  w.terrain.bake(Eigen::AlignedBox2d(Eigen::Vector2d(-150, -150), Eigen::Vector2d(150, 150)), 1.0);
  io::GroundTruthObject far;  // something so the grid exists
  far.object.model = Cylinder{{80, 80, -1}, Eigen::Vector3d::UnitZ(), 0.3, 5};
  w.objects = {far};
  w.renumber();
  const simulator::RayCaster caster(w);
  const Eigen::Vector3d o(0, 0, w.terrain.height(0, 0) + 1.5);
  for (int i = 0; i < 36; ++i) {
    const double a = i * M_PI / 18;
    const Eigen::Vector3d d = Eigen::Vector3d(std::cos(a), std::sin(a), -0.15).normalized();
    simulator::RayHit hit;
    ASSERT_TRUE(caster.cast(o, d, 100, &hit));
    const Eigen::Vector3d p = o + hit.range * d;
    EXPECT_NEAR(p.z(), w.terrain.height(p.x(), p.y()), 0.02) << "azimuth " << a;
  }
}

TEST(Lidar, ScanPointsLieOnTheLabelledObjects) {
  const simulator::World w = twoObjectWorld();
  const simulator::RayCaster caster(w);
  simulator::LidarModel m = simulator::lidarModel("vlp-16");
  m.range_noise = 0.0;
  m.dropout = 0.0;
  std::mt19937_64 rng(1);
  const Pose T = poseFromXyzYaw(0, 0, 1.0, 0.0);
  const io::LabelledScan scan = simulator::simulateLidarScan(caster, T, m, rng);
  ASSERT_TRUE(scan.hasLabels());
  std::size_t trunk = 0, car = 0;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const Eigen::Vector3d p = T * scan.xyz[i].cast<double>();
    if (scan.instance[i] == 1) {
      ++trunk;
      EXPECT_EQ(scan.semantic[i], simulator::label::kTrunk);
      EXPECT_NEAR((p.head<2>() - Eigen::Vector2d(10, 0)).norm(), 0.5, 1e-3);
    } else if (scan.instance[i] == 2) {
      ++car;
      EXPECT_EQ(scan.semantic[i], simulator::label::kCar);
      EXPECT_NEAR(p.y(), 7.0, 1e-3);  // the face towards the sensor
    } else {
      EXPECT_NEAR(p.z(), 0.0, 1e-3);  // ground
    }
  }
  EXPECT_GT(trunk, 20u);
  EXPECT_GT(car, 100u);
  // The trunk spans 2 * asin(0.5 / 10) of azimuth (about 5.7 degrees of 1800 columns); the
  // beams below -6 degrees meet the ground first (tan 6 deg = 1 m / 9.5 m), leaving 11 beams.
  EXPECT_NEAR(static_cast<double>(trunk) / 11, 1800 * 2 * std::asin(0.05) / (2 * M_PI), 2.0);
}

TEST(Lidar, BeamPatterns) {
  EXPECT_EQ(simulator::lidarModel("os1-64").beams(), 64);
  EXPECT_EQ(simulator::lidarModel("hdl-64e").beams(), 64);
  EXPECT_EQ(simulator::lidarModel("vlp-16").beams(), 16);
  EXPECT_NEAR(simulator::lidarModel("hdl-64e").elevation_deg.front(), 2.0, 1e-9);
  EXPECT_NEAR(simulator::lidarModel("hdl-64e").elevation_deg.back(), -24.9, 1e-9);
  EXPECT_THROW(simulator::lidarModel("hdl-32"), std::invalid_argument);
}

TEST(Rgbd, DepthPixelsBackprojectOntoTheKnownObject) {
  const simulator::World w = twoObjectWorld();
  const simulator::RayCaster caster(w);
  simulator::CameraModel cam = simulator::cameraModel("d455");
  cam.invalid_fraction = 0;
  std::mt19937_64 rng(2);
  const Pose T_world_body = poseFromXyzYaw(2, 0, 1.0, 0.0);  // 7.5 m in front of the trunk
  const simulator::RgbdImage img = simulator::renderRgbd(caster, T_world_body, cam, rng);
  ASSERT_EQ(img.depth.type(), CV_16UC1);
  ASSERT_EQ(img.instance_class.size(), img.instance_object.size());
  const int u = static_cast<int>(cam.cx), v = static_cast<int>(cam.cy);
  const uint16_t id = img.instance.at<uint16_t>(v, u);
  ASSERT_GT(id, 0);
  EXPECT_EQ(img.instance_object[id - 1], 1);
  EXPECT_EQ(img.instance_class[id - 1], 71);
  const double z = img.depth.at<uint16_t>(v, u) / 1000.0;
  const double sigma = cam.depth_noise * 7.5 * 7.5;
  EXPECT_NEAR(z, 7.5, 4 * sigma + 0.002);
  // Backproject every trunk pixel: it lands on the trunk surface within the depth noise.
  int checked = 0;
  for (int r = 0; r < cam.height; r += 4)
    for (int c = 0; c < cam.width; c += 4) {
      const uint16_t raw = img.depth.at<uint16_t>(r, c);
      if (img.instance.at<uint16_t>(r, c) != id || raw == 0) continue;
      const double d = raw / 1000.0;
      const Eigen::Vector3d p_cam((c + 0.5 - cam.cx) / cam.fx * d, (r + 0.5 - cam.cy) / cam.fy * d, d);
      const Eigen::Vector3d p = T_world_body * (simulator::R_body_optical() * p_cam);
      EXPECT_NEAR((p.head<2>() - Eigen::Vector2d(10, 0)).norm(), 0.5, 6 * cam.depth_noise * d * d + 0.01);
      ++checked;
    }
  EXPECT_GT(checked, 50);
}
