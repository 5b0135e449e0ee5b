#pragma once
// Spinning LiDAR models with real beam patterns, and a labelled scan simulator.
#include <random>
#include <string>
#include <vector>

#include "geometry/pose.h"
#include "io/kitti_scan.h"
#include "simulator/ray_caster.h"

namespace slide::simulator {

struct LidarModel {
  std::string name;
  std::vector<double> elevation_deg;  // one per beam, top to bottom
  int columns = 1024;                 // firings per revolution
  double min_range = 0.5;             // metres
  double max_range = 100.0;
  double range_noise = 0.02;          // sigma, metres
  double dropout = 0.01;              // probability a return is lost
  // Foliage (vegetation surfaces: bushes, crowns) is not a solid surface: a beam enters it
  // before it returns, by an exponentially distributed depth with this mean (metres); 0
  // renders foliage as solid. 0.06 m gives simulated vegetation the range roughness of the
  // real SemanticKITTI scans (median |r(i-1) - 2 r(i) + r(i+1)| along the scan order: real
  // vegetation 0.077 / 0.086 m in 000720 / 001500, simulated 0.076 m with 2 cm range noise;
  // real cars, trunks and buildings 0.017-0.024 m).
  double foliage_depth = 0.06;
  int beams() const { return static_cast<int>(elevation_deg.size()); }
};

// "os1-64" (Ouster OS1-64: 64 beams over +-16.6 deg, 1024 columns, 120 m),
// "hdl-64e" (Velodyne HDL-64E: +2 to -24.9 deg in two blocks, 2048 columns, 120 m),
// "vlp-16" (Velodyne VLP-16: +-15 deg every 2 deg, 1800 columns, 100 m).
// Throws std::invalid_argument naming the known models for anything else.
LidarModel lidarModel(const std::string& name);
std::vector<std::string> lidarModelNames();

// One sweep from sensor pose T_world_sensor (x forward, y left, z up): points in the sensor
// frame with range noise and dropouts, each labelled with semantic class and instance id.
// Intensity in [0, 1] depends on the surface class and range.
io::LabelledScan simulateLidarScan(const RayCaster& caster, const Pose& T_world_sensor, const LidarModel& model,
                               std::mt19937_64& rng);

}  // namespace slide::simulator
