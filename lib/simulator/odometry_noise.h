#pragma once
// Odometry like a VIO/LIO estimate: drift grows with distance travelled (a share of the
// distance in position, degrees per metre in yaw), with slowly wandering (random-walk) biases;
// roll and pitch stay nearly exact (gravity is observable). The odometry frame is the robot's
// own: gravity-aligned, at its start position with its start heading.
#include <random>
#include <vector>

#include "geometry/pose.h"

namespace slide::simulator {

struct OdometryNoise {
  double translation_drift = 0.01;    // position error std as a fraction of distance (1 %)
  double yaw_drift_deg_per_m = 0.01;  // std of the yaw-rate bias, degrees per metre
  double bias_walk = 0.1;             // bias random walk: fraction of its std per sqrt(metre / 100)
  double vertical_drift = 0.002;      // z error std as a fraction of distance
  double roll_pitch_noise_deg = 0.05; // white noise on roll and pitch, degrees
};

// Odometry poses (in the robot's odometry frame) for ground-truth body poses (world frame).
// Element 0 is the identity up to roll/pitch: the odometry origin is gravity aligned.
std::vector<Pose> simulateOdometry(const std::vector<Pose>& ground_truth, const OdometryNoise& noise,
                                   std::mt19937_64& rng);

// World pose of the odometry frame of a robot whose first ground-truth pose is T0 (4-DoF:
// its position and yaw).
Pose odometryOrigin(const Pose& T0);

}  // namespace slide::simulator
