#include <gtest/gtest.h>

#include "mapped_robot/sensor_rig.h"

using namespace slide;

TEST(SensorRig, ParsesKindAndModel) {
  const mapped_robot::SensorRig l = mapped_robot::parseSensorRig("lidar:vlp-16");
  EXPECT_EQ(l.kind, mapped_robot::SensorRig::Kind::Lidar);
  EXPECT_EQ(l.model, "vlp-16");
  const mapped_robot::SensorRig c = mapped_robot::parseSensorRig("rgbd:d435");
  EXPECT_EQ(c.kind, mapped_robot::SensorRig::Kind::Rgbd);
  EXPECT_THROW(mapped_robot::parseSensorRig("sonar:x"), std::invalid_argument);
  EXPECT_THROW(mapped_robot::parseSensorRig("lidar:nope"), std::invalid_argument);
  EXPECT_THROW(mapped_robot::parseSensorRig("rgbd"), std::invalid_argument);
}

TEST(SensorRig, PitchedMountLooksDown) {
  const Pose T = mapped_robot::pitchedMount(90.0, 0.3);
  const Eigen::Vector3d forward = T.linear() * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(forward.z(), -1.0, 1e-12);
  EXPECT_NEAR(T.translation().z(), 0.3, 1e-12);
  const Eigen::Vector3d f30 = mapped_robot::pitchedMount(30.0).linear() * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(f30.z(), -0.5, 1e-12);
  EXPECT_NEAR(f30.y(), 0.0, 1e-12);
}

TEST(SensorRig, RgbdFrameKeepsImagesAndClasses) {
  const simulator::CameraModel cam = simulator::cameraModel("d455");
  simulator::RgbdImage img;
  img.depth = cv::Mat(cam.height, cam.width, CV_16UC1, cv::Scalar(1500));
  img.instance = cv::Mat(cam.height, cam.width, CV_16UC1, cv::Scalar(0));
  img.instance.at<std::uint16_t>(3, 4) = 1;
  img.instance_class = {2};
  const frontend::RgbdFrame f = mapped_robot::rgbdFrameOf(img, cam);
  ASSERT_EQ(f.depth.size(), static_cast<std::size_t>(cam.width * cam.height));
  EXPECT_EQ(f.depth[0], 1500);
  EXPECT_EQ(f.mask[3 * cam.width + 4], 1);
  EXPECT_EQ(f.instance_class, std::vector<int>{2});
  EXPECT_EQ(f.instance_confidence.size(), 1u);
  EXPECT_EQ(f.intrinsics.fx, cam.fx);
}
