#pragma once
// A robot's object map as its own odometry bends it (tooling: the place benchmark and its tests).
// The robot drives a route through a world of objects; each object it passes within `range` is
// placed with the odometry pose of its closest approach on the first pass, so the map bends
// with the drift accumulated up to there (yaw bias, distance scale error, height drift). On top:
// position and size noise, missed objects, spurious objects of the classes and sizes the map
// holds, and class confusion. The map is in the robot's odometry frame: its start pose on the
// route, gravity aligned.
#include <map>
#include <random>
#include <vector>

#include "place/landmark.h"

namespace slide::simulator {

struct MapErrorParams {
  double yaw_drift_deg_per_100m = 1.5;   // odometry yaw bias; its sign is drawn per map
  double scale_error = 0.005;            // odometry distance scale error (sign drawn per map)
  double vertical_drift_per_100m = 0.3;  // metres of height error per 100 m (sign drawn per map)
  double range = 15;                     // metres: objects this close (horizontally) to the route are seen
  double position_sigma = 0.2;           // metres per axis, on every mapped object
  double size_sigma = 0.05;              // metres per extent (known extents only)
  double missed = 0.2;                   // chance that a seen object is missing from the map
  double spurious = 0.2;                 // chance per mapped true object of one false object
  double confusion = 0.075;              // chance that a mapped object carries a confusable class
};

// For each class, the classes a detector mistakes it for (one is drawn uniformly). A class with
// no entry is never confused.
using ClassConfusions = std::map<int, std::vector<int>>;

// Landmark::index of a spurious object (true objects keep their world index).
inline constexpr std::size_t kSpuriousObject = static_cast<std::size_t>(-1);

struct DriftedMap {
  std::vector<place::Landmark> lms;      // in the odometry frame
  std::vector<int> true_class;    // per landmark: the world object's class (false ones: the class given)
  std::vector<double> seen_at;    // per landmark: metres along the route when it was placed
  Pose T_w_r = Pose::Identity();  // world pose of the odometry frame (the route's first pose)
  std::vector<Pose> truth;        // route poses in the world, one per step
  std::vector<Pose> odometry;     // the same poses as the drifting odometry has them (odometry frame)
  std::vector<double> s;          // metres along the route of each pose
  double yaw_rate = 0;            // drawn yaw bias, radians per metre (signed)
};

// Poses along a polyline (world x, y; z = 0), one every `step` metres and at its end, heading
// along the segment. Fewer than two distinct points give no poses.
std::vector<Pose> posesAlong(const std::vector<Eigen::Vector2d>& route, double step);

// Dead reckoning over `truth` (world poses): each step's relative motion with its length scaled
// by (1 + scale_error), an extra yaw of yaw_rate per metre and an extra height of dz_per_m per
// metre. Starts at the identity (the odometry frame is the first true pose).
std::vector<Pose> driftedOdometry(const std::vector<Pose>& truth, double yaw_rate, double scale_error, double dz_per_m);

// The map of `world` (landmarks with world indices) made by a robot driving `route`.
DriftedMap mapAlongRoute(const std::vector<place::Landmark>& world, const std::vector<Eigen::Vector2d>& route,
                         const MapErrorParams& params, const ClassConfusions& confusions, std::mt19937& rng);

// The landmarks of `m` placed within the first `s_max` metres of its route (the map then).
std::vector<place::Landmark> mapUpTo(const DriftedMap& m, double s_max);

// Truth between two maps of one world: the least-squares 4-DoF (x, y, z, yaw) transform T_a_b over
// the world objects both hold, at the positions the maps give them (spurious objects excluded;
// an object both hold twice counts once, at its first landmark). Not ok below 3 shared objects.
struct SharedTruth {
  bool ok = false;
  Pose T_a_b = Pose::Identity();
  std::size_t shared = 0;
  Eigen::Vector3d centroid_b = Eigen::Vector3d::Zero();  // of the shared objects, in B's frame
  double rms = 0;                                        // residual of the fit, metres
};
SharedTruth sharedObjectTruth(const std::vector<place::Landmark>& a, const std::vector<place::Landmark>& b);

}  // namespace slide::simulator
