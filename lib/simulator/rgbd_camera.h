#pragma once
// Depth cameras (Intel RealSense D435 / D455 at 640x480) and an RGBD frame renderer: colour
// image, 16-bit depth in millimetres with noise growing with range squared and invalid (0)
// pixels, and an instance mask with the class of each instance.
#include <random>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "geometry/pose.h"
#include "simulator/ray_caster.h"

namespace slide::simulator {

struct CameraModel {
  std::string name;
  int width = 640, height = 480;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  double min_depth = 0.3, max_depth = 10.0;  // metres
  double depth_noise = 0.005;  // depth sigma = depth_noise * z^2 (metres, z in metres)
  double invalid_fraction = 0.01;  // pixels randomly without depth
};

// "d435" (fx 615, 10 m) or "d455" (fx 390, 12 m, lower noise), both 640x480.
// Throws std::invalid_argument naming the known models otherwise.
CameraModel cameraModel(const std::string& name);
std::vector<std::string> cameraModelNames();

// Rotation from the camera's optical frame (x right, y down, z forward) to the body frame
// (x forward, y left, z up). The camera sits at the body origin.
Eigen::Matrix3d R_body_optical();

struct RgbdImage {
  cv::Mat color;     // CV_8UC3, BGR
  cv::Mat depth;     // CV_16UC1, millimetres, 0 = invalid
  cv::Mat instance;  // CV_16UC1, per-frame instance id 1..K, 0 = none
  std::vector<int> instance_class;     // class id (classes.yaml) of instance i + 1
  std::vector<int> instance_object;    // ground-truth object id of instance i + 1
};

// Renders a frame from body pose T_world_body.
RgbdImage renderRgbd(const RayCaster& caster, const Pose& T_world_body, const CameraModel& camera,
                     std::mt19937_64& rng);

}  // namespace slide::simulator
