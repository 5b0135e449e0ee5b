#pragma once
// The paper's heterogeneous cases: two simulated robots with different sensors map the same
// world through the real front-end and back-end (lib/mapped_robot), each in its own odometry frame;
// place recognition then aligns the two object maps and is scored against the simulator's
// truth. lidar_rgbd: an OS1-64 LiDAR robot and a D455 RGBD robot in the indoor world.
// aerial_ground: two D455 robots in the urban parking lot, one flying above the aisles
// looking down, one driving them looking forward (the flyer retraces the driver's route
// backwards, so both see the same cars, from above and from the aisle).
#include <optional>
#include <string>

#include "place/place_config.h"

namespace slide::bench_place {

struct HeteroSpec {
  std::string name;            // hetero_lidar_rgbd | hetero_aerial_ground
  std::string world;           // indoor | urban
  std::string sensor_a, sensor_b;  // lidar:<model> | rgbd:<model>
  double pitch_a_deg = 0, pitch_b_deg = 0;  // camera pitch below the horizon
  bool retrace_b = false;      // B follows A's route backwards instead of its own
  double climb_b = 0;          // metres B flies above that route (0: ground robot)
  double distance = 40;        // metres per robot
  double overlap = 0.6;        // shared share of the routes
  double rate = 2;             // frames per second
  std::uint64_t seed = 1;
  std::string description;
};

HeteroSpec heteroLidarRgbd(std::uint64_t seed);
HeteroSpec heteroAerialGround(std::uint64_t seed);

struct HeteroMethod {
  bool found = false;
  double trans_err_m = 0, yaw_err_deg = 0, cpu_ms = 0;
  std::size_t inliers = 0;
  std::string reason;  // why no transform
};

struct HeteroFigures {
  int objects_a = 0, objects_b = 0;  // confirmed landmarks in each robot's map
  int true_a = 0, true_b = 0, shared = 0;  // of them near a true object; true objects in both
  double err_a = 0, err_b = 0;       // median horizontal distance of those to their true object
  int frames_a = 0, frames_b = 0, keyposes_a = 0, keyposes_b = 0;
  double map_cpu_s_a = 0, map_cpu_s_b = 0;  // simulation + front-end + back-end
  double wall_s = 0;
  HeteroMethod slidegraph, slidematch;
};

HeteroFigures runHetero(const HeteroSpec& spec, const place::PlaceConfig& config, int repeats);

}  // namespace slide::bench_place
