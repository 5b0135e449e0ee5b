#pragma once
// Hand-made labelled LiDAR scans for front-end tests: points on the sensor-facing surfaces of
// upright cylinders (trunks, class 71) and boxes (cars, class 10) plus flat ground where no
// object hides it, with SemanticKITTI labels and instance ids (object index + 1).
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "geometry/pose.h"
#include "io/kitti_scan.h"

namespace slide::synth {

struct SceneObject {
  int semantic = 71;              // 71 trunk (cylinder) or 10 car (box)
  Eigen::Vector3d center;         // world frame; cylinders: axis bottom (on the ground)
  double radius = 0.2;            // cylinders
  double height = 6.0;
  double yaw = 0;                 // boxes
  Eigen::Vector3d dims{4.4, 1.8, 1.5};  // boxes (length, width, height)
};

// Scan seen from T_world_sensor (sensor 1.5 m above the ground at z = 0 of the world), points
// in the sensor frame, spacing ~`step` metres on each surface (`ground_step` on the ground).
inline io::LabelledScan syntheticScan(const std::vector<SceneObject>& objects, const Pose& T_world_sensor,
                                  double step = 0.05, unsigned seed = 1, double noise = 0.01,
                                  double ground_step = 0.2) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, noise);
  io::LabelledScan s;
  const Pose T_sensor_world = T_world_sensor.inverse();
  const Eigen::Vector3d eye = T_world_sensor.translation();
  auto add = [&](const Eigen::Vector3d& p, int sem, int inst) {
    const Eigen::Vector3d q = T_sensor_world * (p + Eigen::Vector3d(n(rng), n(rng), n(rng)));
    s.xyz.push_back(q.cast<float>());
    s.intensity.push_back(0.5f);
    s.semantic.push_back(static_cast<uint16_t>(sem));
    s.instance.push_back(static_cast<uint16_t>(inst));
  };
  // Whether an object stands between the sensor and world point p (the line of sight ends there).
  auto hidden = [&](const Eigen::Vector3d& p) {
    for (const SceneObject& o : objects) {
      if (o.semantic == 10) {  // slab test in the box's frame
        const Eigen::Matrix3d Rt = rotZ(o.yaw).transpose();
        const Eigen::Vector3d half = o.dims / 2;
        const Eigen::Vector3d a = Rt * (eye - o.center - Eigen::Vector3d(0, 0, half.z()));
        const Eigen::Vector3d d = Rt * (p - eye);
        double t0 = 0, t1 = 1;
        for (int k = 0; k < 3 && t0 <= t1; ++k) {
          if (std::abs(d[k]) < 1e-12) {
            if (std::abs(a[k]) > half[k]) t1 = -1;
            continue;
          }
          const double ta = (-half[k] - a[k]) / d[k], tb = (half[k] - a[k]) / d[k];
          t0 = std::max(t0, std::min(ta, tb)), t1 = std::min(t1, std::max(ta, tb));
        }
        if (t0 <= t1 && t0 < 1 - 1e-9) return true;  // it enters the box before p (ground under the box too)
      } else {  // the line of sight's nearest approach to the axis, below the top
        const Eigen::Vector2d e = eye.head<2>(), d = (p - eye).head<2>();
        const double t = std::clamp((o.center.head<2>() - e).dot(d) / std::max(d.squaredNorm(), 1e-12), 0.0, 1.0);
        const double z = eye.z() + t * (p.z() - eye.z());
        if (t < 1 - 1e-9 && (e + t * d - o.center.head<2>()).norm() < o.radius && z < o.center.z() + o.height) return true;
      }
    }
    return false;
  };
  // Ground ring around the sensor, where no object hides it.
  for (double r = 2.0; r < 20.0; r += ground_step)
    for (double a = 0; a < 2 * M_PI; a += ground_step / r) {
      const Eigen::Vector3d g = eye + Eigen::Vector3d(r * std::cos(a), r * std::sin(a), -eye.z());
      if (!hidden(g)) add(g, 40, 0);
    }
  for (std::size_t k = 0; k < objects.size(); ++k) {
    const SceneObject& o = objects[k];
    const int inst = static_cast<int>(k) + 1;
    if (o.semantic == 10) {
      const Eigen::Matrix3d R = rotZ(o.yaw);
      const Eigen::Vector3d half = o.dims / 2;
      const Eigen::Vector3d c = o.center + Eigen::Vector3d(0, 0, half.z());
      for (int axis = 0; axis < 3; ++axis)
        for (int sign = -1; sign <= 1; sign += 2) {
          Eigen::Vector3d nrm = Eigen::Vector3d::Zero();
          nrm[axis] = sign;
          const Eigen::Vector3d face = c + R * (nrm.cwiseProduct(half));
          if ((R * nrm).dot(eye - face) <= 0 || (axis == 2 && sign < 0)) continue;
          const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
          for (double u = -half[a1]; u <= half[a1]; u += step)
            for (double v = -half[a2]; v <= half[a2]; v += step) {
              Eigen::Vector3d local = nrm.cwiseProduct(half);
              local[a1] = u;
              local[a2] = v;
              add(c + R * local, 10, inst);
            }
        }
    } else {
      const Eigen::Vector2d to_eye = (eye - o.center).head<2>().normalized();
      for (double z = 0; z <= o.height; z += step)
        for (double a = -M_PI / 2; a <= M_PI / 2; a += step / o.radius) {
          const double ang = std::atan2(to_eye.y(), to_eye.x()) + a;
          add(o.center + Eigen::Vector3d(o.radius * std::cos(ang), o.radius * std::sin(ang), z), o.semantic, inst);
        }
    }
  }
  return s;
}

}  // namespace slide::synth
