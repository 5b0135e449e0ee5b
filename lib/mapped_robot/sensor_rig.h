#pragma once
// What a simulated robot carries: one LiDAR (labelled segmentation) or one RGBD camera
// (instance masks), mounted on the body with a known pose. Helpers to build a pitched
// camera mount and to turn a rendered RGBD image into the front-end's frame type.
#include <string>

#include "frontend/rgbd_segmenter.h"
#include "geometry/pose.h"
#include "simulator/rgbd_camera.h"

namespace slide::mapped_robot {

struct SensorRig {
  enum class Kind { Lidar, Rgbd };
  Kind kind = Kind::Lidar;
  std::string model = "os1-64";            // lidarModel() or cameraModel() name
  Pose T_body_sensor = Pose::Identity();   // sensor frame (x forward, y left, z up) in the body
};

// "lidar:<model>" or "rgbd:<model>" (e.g. lidar:os1-64, rgbd:d455), identity mount.
// Throws std::invalid_argument naming the accepted forms and models.
SensorRig parseSensorRig(const std::string& spec);

// A sensor looking `pitch_down_deg` below the body's x axis, `up` metres above the body origin.
Pose pitchedMount(double pitch_down_deg, double up = 0.0);

// The front-end's view of a rendered frame: depth, instance mask and classes (confidence 1).
frontend::RgbdFrame rgbdFrameOf(const simulator::RgbdImage& img, const simulator::CameraModel& camera);

}  // namespace slide::mapped_robot
