#include "simulator/terrain.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace slide::simulator {

Eigen::Vector2d HeightGrid::gradient(double x, double y) const {
  const double h = 0.25 * cell;
  return {(height(x + h, y) - height(x - h, y)) / (2 * h), (height(x, y + h) - height(x, y - h)) / (2 * h)};
}

void HeightGrid::finish() {
  double s = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double v = z[static_cast<std::size_t>(j) * nx + i];
      if (i + 1 < nx) s = std::max(s, std::abs(z[static_cast<std::size_t>(j) * nx + i + 1] - v) / cell);
      if (j + 1 < ny) s = std::max(s, std::abs(z[static_cast<std::size_t>(j + 1) * nx + i] - v) / cell);
    }
  slope_bound = 1.5 * s;  // bilinear patches can be steeper along diagonals
  z_lo = z.empty() ? 0 : *std::min_element(z.begin(), z.end());
  z_hi = z.empty() ? 0 : *std::max_element(z.begin(), z.end());
}

double Terrain::heightWithWaves(double x, double y) const {
  double z = base_z + (grid.empty() ? 0.0 : grid.height(x, y));
  for (const TerrainWave& w : waves) z += w.amplitude * std::sin(w.kx * x + w.ky * y + w.phase);
  return z;
}

void Terrain::bake(const Eigen::AlignedBox2d& box, double cell) {
  HeightGrid g;
  g.cell = cell;
  g.origin = box.min();
  g.nx = static_cast<int>(std::ceil(box.sizes().x() / cell)) + 1;
  g.ny = static_cast<int>(std::ceil(box.sizes().y() / cell)) + 1;
  g.z.resize(static_cast<std::size_t>(g.nx) * g.ny);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) g.z[static_cast<std::size_t>(j) * g.nx + i] = height(g.origin.x() + i * cell, g.origin.y() + j * cell) - base_z;
  g.finish();
  grid = std::move(g);
  waves.clear();
}

Eigen::Vector2d Terrain::gradient(double x, double y) const {
  Eigen::Vector2d g = grid.empty() ? Eigen::Vector2d::Zero() : grid.gradient(x, y);
  for (const TerrainWave& w : waves) {
    const double c = w.amplitude * std::cos(w.kx * x + w.ky * y + w.phase);
    g += c * Eigen::Vector2d(w.kx, w.ky);
  }
  return g;
}

double Terrain::intersectCeiling(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range) const {
  if (!ceiling_z || d.z() <= 1e-9) return std::numeric_limits<double>::infinity();
  const double t = (*ceiling_z - o.z()) / d.z();
  return t > 0 && t < max_range ? t : std::numeric_limits<double>::infinity();
}

double Terrain::minHeight() const {
  double amp = 0;
  for (const TerrainWave& w : waves) amp += std::abs(w.amplitude);
  return base_z - amp + (grid.empty() ? 0.0 : grid.z_lo);
}

double Terrain::maxHeight() const {
  double amp = 0;
  for (const TerrainWave& w : waves) amp += std::abs(w.amplitude);
  return base_z + amp + (grid.empty() ? 0.0 : grid.z_hi);
}

double Terrain::intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range,
                          uint16_t* hit_semantic, double t_start) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double best = kInf;
  if (ceiling_z && d.z() > 1e-9) {
    const double t = (*ceiling_z - o.z()) / d.z();
    if (t > 0 && t < max_range) best = t, *hit_semantic = ceiling_semantic;
  }
  auto g = [&](double t) { return o.z() + t * d.z() - height(o.x() + t * d.x(), o.y() + t * d.y()); };
  if (g(t_start) <= 0) return best;  // start below ground: no hit
  double t_ground = kInf;
  if (waves.empty() && grid.empty()) {
    if (d.z() < -1e-12) t_ground = (base_z - o.z()) / d.z();
    if (t_ground < t_start) t_ground = kInf;
  } else {
    // Lipschitz marching (the ray cannot meet the ground closer than g / L), then false position.
    double amp = 0, slope = 0;
    for (const TerrainWave& w : waves) {
      amp += std::abs(w.amplitude);
      slope += std::abs(w.amplitude) * std::hypot(w.kx, w.ky);
    }
    double zmin = base_z - amp, zmax = base_z + amp;
    if (!grid.empty()) {
      zmin += grid.z_lo;
      zmax += grid.z_hi;
      slope += grid.slope_bound;
    }
    double t0 = t_start, t1 = max_range;
    const double zs = o.z() + t_start * d.z();
    if (d.z() < -1e-12) {
      t1 = std::min(max_range, (zmin - o.z()) / d.z());
      if (zs > zmax) t0 = std::max(t_start, (zmax - o.z()) / d.z());
    } else if (zs >= zmax) {
      t1 = -1;  // above the highest hill, going up or level: no ground hit
    } else if (d.z() > 1e-12) {
      t1 = std::min(max_range, (zmax - o.z()) / d.z());
    }
    const double lipschitz = std::abs(d.z()) + slope * std::sqrt(d.x() * d.x() + d.y() * d.y()) + 1e-9;
    double a = t0, ga = g(a);
    while (a < t1) {
      const double b = std::min(a + std::max(ga / lipschitz, std::max(0.4, 0.04 * a)), t1);
      const double gb = g(b);
      if (gb <= 0) {
        // False position (the ground is smooth), bisection as a fallback.
        double lo = a, hi = b, glo = ga, ghi = gb, t = b;
        for (int i = 0; i < 12 && hi - lo > 1e-3; ++i) {
          t = i < 4 ? lo + (hi - lo) * glo / (glo - ghi) : 0.5 * (lo + hi);
          const double gt = g(t);
          if (std::abs(gt) < 1e-3) break;
          if (gt > 0) lo = t, glo = gt;
          else hi = t, ghi = gt;
        }
        t_ground = t;
        break;
      }
      a = b, ga = gb;
    }
  }
  if (t_ground > 0 && t_ground < max_range && t_ground < best) best = t_ground, *hit_semantic = semantic;
  return best;
}

Terrain unevenTerrain(double amplitude, uint64_t seed, uint16_t semantic) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Terrain t;
  t.semantic = semantic;
  for (int i = 0; i < 4; ++i) {
    const double wavelength = 30 + 50 * u(rng);
    const double dir = 2 * M_PI * u(rng);
    const double k = 2 * M_PI / wavelength;
    t.waves.push_back({amplitude * (0.25 + 0.25 * u(rng)), k * std::cos(dir), k * std::sin(dir), 2 * M_PI * u(rng)});
  }
  return t;
}

}  // namespace slide::simulator
