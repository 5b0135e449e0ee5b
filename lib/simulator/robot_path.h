#pragma once
// Robot routes over a world's route graph and the smooth trajectories that follow them.
#include <random>
#include <vector>

#include "geometry/pose.h"
#include "simulator/world.h"

namespace slide::simulator {

struct MotionParams {
  bool aerial = false;
  double speed = 1.5;                // m/s
  double rate = 10.0;                // frames per second
  double height = 0.8;               // ground: sensor above the terrain; aerial: mean altitude
  double altitude_amplitude = 1.5;   // aerial: altitude swing, metres
  double altitude_wavelength = 40;   // aerial: metres of travel per altitude cycle
  double corner_radius = 1.5;        // metres of smoothing at route corners
  double max_yaw_rate = 1.0;         // rad/s: sharper turns (a route doubling back) are made in place
};

// Body poses (x forward, y left, z up) in the world frame at frame times.
struct Trajectory {
  std::vector<double> times;
  std::vector<Pose> poses;
  std::size_t size() const { return poses.size(); }
  double length() const;  // metres travelled
};

// One polyline per robot, each at least `length` metres long (when the graph allows): robots
// start far apart; a share `overlap` (0..1) of every route runs along one common walk all
// robots drive (in their own order), the rest explores on their own.
std::vector<std::vector<Eigen::Vector2d>> planRoutes(const RouteGraph& graph, int robots, double length,
                                                     double overlap, std::mt19937_64& rng);

// Follows the polyline at constant speed with rounded corners for at most `max_length`
// metres (and at most max_frames frames when > 0), starting at time t0. Where the path turns
// faster than max_yaw_rate (a route that doubles back turns 180 degrees within a few frames), the
// robot stops and turns in place at max_yaw_rate first. Ground robots stay `height` above the
// terrain and tilt with its slope; aerial robots change altitude.
Trajectory followRoute(const std::vector<Eigen::Vector2d>& polyline, const Terrain& terrain, const MotionParams& motion,
                       double max_length, int max_frames = 0, double t0 = 0);

}  // namespace slide::simulator
