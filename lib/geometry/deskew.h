#pragma once
// Motion compensation (deskew) of one LiDAR sweep from per-point times: point i, measured at
// t_ref + dt[i] in the body frame of that instant, is moved into the body frame at t_ref:
//   p' = T_odom_body(t_ref)^-1 * T_odom_body(t_ref + dt[i]) * p.
// Poses are looked up on a grid of `resolution_s` over the sweep's time span (nearest grid
// time; 0.1 ms moves a point 5 mm at 1 rad/s and 50 m). Points whose time has no pose are
// flagged, not moved by a guess.
// Vocabulary: in namespace slide itself, not slide::geometry, as every area uses it (README).
#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "geometry/stamped_pose.h"

namespace slide {

using PoseLookup = std::function<PoseMiss(double t, Pose& T_odom_body)>;

// Deskews xyz in place; returns one flag per point, 0 where no pose existed (the caller drops
// those). Throws std::invalid_argument when sizes differ; no pose at t_ref flags every point.
std::vector<uint8_t> deskewSweep(std::vector<Eigen::Vector3f>& xyz, const std::vector<double>& dt, double t_ref,
                                 const PoseLookup& T_odom_body_at, double resolution_s = 1e-4);

}  // namespace slide
