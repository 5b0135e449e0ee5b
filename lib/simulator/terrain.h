#pragma once
// Ground (and optional ceiling) of a world: a smooth height field z = base + sum of waves.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "simulator/semantic_labels.h"

namespace slide::simulator {

struct TerrainWave {
  double amplitude = 0;  // metres
  double kx = 0, ky = 0;  // radians per metre
  double phase = 0;
};

// Heights on a regular x-y grid, interpolated bilinearly (clamped at the edges).
struct HeightGrid {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double cell = 5.0;
  int nx = 0, ny = 0;
  std::vector<double> z;  // row-major, z[iy * nx + ix]
  bool empty() const { return z.empty(); }
  double height(double x, double y) const {
    const double fx = std::clamp((x - origin.x()) / cell, 0.0, nx - 1.001);
    const double fy = std::clamp((y - origin.y()) / cell, 0.0, ny - 1.001);
    const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
    const double ax = fx - ix, ay = fy - iy;
    const double* r0 = &z[static_cast<std::size_t>(iy) * nx + ix];
    const double* r1 = r0 + nx;
    return (1 - ay) * ((1 - ax) * r0[0] + ax * r0[1]) + ay * ((1 - ax) * r1[0] + ax * r1[1]);
  }
  Eigen::Vector2d gradient(double x, double y) const;
  // Call after filling z: caches the height range and a bound on the slope.
  void finish();
  double z_lo = 0, z_hi = 0, slope_bound = 0;
};

struct Terrain {
  double base_z = 0;
  HeightGrid grid;  // added to base_z and the waves
  std::vector<TerrainWave> waves;
  uint16_t semantic = label::kTerrain;
  std::optional<double> ceiling_z;  // indoor worlds: a flat ceiling
  uint16_t ceiling_semantic = label::kOtherStructure;

  double height(double x, double y) const {
    return waves.empty() ? base_z + (grid.empty() ? 0.0 : grid.height(x, y)) : heightWithWaves(x, y);
  }
  Eigen::Vector2d gradient(double x, double y) const;
  // Samples the whole terrain (waves included) into `grid` over `box` every `cell` metres and
  // drops the waves: heights become cheap bilinear look-ups (ray casting speed).
  void bake(const Eigen::AlignedBox2d& box, double cell);
  // Distance along the unit ray (o, d) to the ground or ceiling, +inf when none before
  // max_range; `semantic` receives the label of the surface hit.
  // The search starts at t_start (the ray must be above ground there).
  double intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range, uint16_t* semantic,
                   double t_start = 0) const;
  // Ceiling only: distance to it along the ray, +inf when none before max_range.
  double intersectCeiling(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range) const;
  // Lowest and highest ground height anywhere.
  double minHeight() const;
  double maxHeight() const;
  double heightWithWaves(double x, double y) const;
  bool flat() const { return waves.empty() && grid.empty(); }
};

// Gentle random hills: `amplitude` metres peak, wavelengths between 30 and 80 m.
Terrain unevenTerrain(double amplitude, uint64_t seed, uint16_t semantic = label::kTerrain);

}  // namespace slide::simulator
