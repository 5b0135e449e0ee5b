#include "mapped_robot/sensor_rig.h"

#include <cmath>
#include <stdexcept>

#include "simulator/lidar.h"

namespace slide::mapped_robot {

SensorRig parseSensorRig(const std::string& spec) {
  const auto colon = spec.find(':');
  const std::string kind = spec.substr(0, colon), model = colon == std::string::npos ? "" : spec.substr(colon + 1);
  SensorRig rig;
  rig.model = model;
  if (kind == "lidar") {
    rig.kind = SensorRig::Kind::Lidar;
    simulator::lidarModel(model);  // throws naming the known models
  } else if (kind == "rgbd") {
    rig.kind = SensorRig::Kind::Rgbd;
    simulator::cameraModel(model);
  } else {
    throw std::invalid_argument("sensor '" + spec + "': expected lidar:<model> or rgbd:<model>");
  }
  return rig;
}

Pose pitchedMount(double pitch_down_deg, double up) {
  Pose T = Pose::Identity();
  // A positive rotation about y turns x (forward) towards -z (down).
  T.linear() = Eigen::AngleAxisd(pitch_down_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0, 0, up);
  return T;
}

frontend::RgbdFrame rgbdFrameOf(const simulator::RgbdImage& img, const simulator::CameraModel& camera) {
  frontend::RgbdFrame f;
  f.intrinsics = {camera.width, camera.height, camera.fx, camera.fy, camera.cx, camera.cy, 0.001};
  f.depth.assign(img.depth.begin<std::uint16_t>(), img.depth.end<std::uint16_t>());
  f.mask.assign(img.instance.begin<std::uint16_t>(), img.instance.end<std::uint16_t>());
  f.instance_class = img.instance_class;
  f.instance_confidence.assign(img.instance_class.size(), 1.0f);
  return f;
}

}  // namespace slide::mapped_robot
