#pragma once
// Ground (and optional ceiling) of a world: a smooth height field z = base + sum of waves.
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "sim/semantic_labels.h"

namespace slide {

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
  double height(double x, double y) const;
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

  double height(double x, double y) const;
  Eigen::Vector2d gradient(double x, double y) const;
  // Distance along the unit ray (o, d) to the ground or ceiling, +inf when none before
  // max_range; `semantic` receives the label of the surface hit.
  double intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range, uint16_t* semantic) const;
};

// Gentle random hills: `amplitude` metres peak, wavelengths between 30 and 80 m.
Terrain unevenTerrain(double amplitude, uint64_t seed, uint16_t semantic = label::kTerrain);

}  // namespace slide
