#include "simulator/rgbd_camera.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "simulator/semantic_labels.h"

namespace slide::simulator {

std::vector<std::string> cameraModelNames() { return {"d435", "d455"}; }

CameraModel cameraModel(const std::string& name) {
  CameraModel c;
  c.name = name;
  if (name == "d435") {
    c.fx = c.fy = 615.0;
    c.cx = 320.0, c.cy = 240.0;
    c.max_depth = 10.0;
    c.depth_noise = 0.008;
  } else if (name == "d455") {
    c.fx = c.fy = 390.0;
    c.cx = 320.0, c.cy = 240.0;
    c.max_depth = 12.0;
    c.depth_noise = 0.004;
  } else {
    throw std::invalid_argument("unknown camera model '" + name + "' (known: d435, d455)");
  }
  return c;
}

Eigen::Matrix3d R_body_optical() {
  Eigen::Matrix3d R;
  R << 0, 0, 1,  //
      -1, 0, 0,  //
      0, -1, 0;
  return R;
}

namespace {
cv::Vec3b baseColor(uint16_t semantic) {  // BGR
  switch (semantic) {
    case label::kCar: return {60, 60, 200};
    case label::kTrunk: return {40, 70, 110};
    case label::kPole: return {170, 170, 170};
    case label::kVegetation: return {50, 140, 50};
    case label::kTerrain: return {60, 110, 120};
    case label::kRoad:
    case label::kParking: return {90, 90, 90};
    case label::kBuilding: return {200, 200, 190};
    case label::kChair: return {40, 120, 220};
    case label::kTable: return {60, 100, 150};
    case label::kMonitor: return {30, 30, 30};
    case label::kOtherGround: return {150, 160, 170};
    case label::kOtherStructure: return {230, 230, 230};
    default: return {180, 120, 160};
  }
}
}  // namespace

RgbdImage renderRgbd(const RayCaster& caster, const Pose& T_world_body, const CameraModel& cam, std::mt19937_64& rng) {
  RgbdImage img;
  img.color = cv::Mat(cam.height, cam.width, CV_8UC3, cv::Scalar(235, 206, 135));  // sky
  img.depth = cv::Mat::zeros(cam.height, cam.width, CV_16UC1);
  img.instance = cv::Mat::zeros(cam.height, cam.width, CV_16UC1);
  std::normal_distribution<double> n01(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  const Eigen::Matrix3d R = T_world_body.linear() * R_body_optical();
  const Eigen::Vector3d o = T_world_body.translation();
  std::map<uint16_t, uint16_t> local_id;  // object id -> per-frame instance id
  const OriginView view(caster, o, 100.0);
  RayHit hit;
  for (int v = 0; v < cam.height; ++v) {
    auto* color = img.color.ptr<cv::Vec3b>(v);
    auto* depth = img.depth.ptr<uint16_t>(v);
    auto* inst = img.instance.ptr<uint16_t>(v);
    for (int c = 0; c < cam.width; ++c) {
      const Eigen::Vector3d ray_cam((c + 0.5 - cam.cx) / cam.fx, (v + 0.5 - cam.cy) / cam.fy, 1.0);
      const double norm = ray_cam.norm();
      if (!view.cast(R * (ray_cam / norm), 100.0, &hit)) continue;
      const double z = hit.range / norm;  // depth along the optical axis
      const double shade = std::clamp(1.1 - 0.04 * z, 0.35, 1.0) * (0.9 + 0.1 * u(rng));
      const cv::Vec3b base = baseColor(hit.semantic);
      const int tint = hit.instance ? (hit.instance * 37) % 41 - 20 : 0;
      for (int k = 0; k < 3; ++k) color[c][k] = cv::saturate_cast<uchar>((base[k] + tint) * shade);
      if (hit.instance) {
        auto it = local_id.find(hit.instance);
        if (it == local_id.end()) {
          it = local_id.emplace(hit.instance, static_cast<uint16_t>(local_id.size() + 1)).first;
          img.instance_object.push_back(hit.instance);
          img.instance_class.push_back(label::classIdOfLabel(hit.semantic));
        }
        inst[c] = it->second;
      }
      if (z < cam.min_depth || z > cam.max_depth || u(rng) < cam.invalid_fraction) continue;
      const double zn = z + cam.depth_noise * z * z * n01(rng);
      if (zn > 0) depth[c] = static_cast<uint16_t>(std::min(65535.0, std::round(zn * 1000.0)));
    }
  }
  return img;
}

}  // namespace slide::simulator
