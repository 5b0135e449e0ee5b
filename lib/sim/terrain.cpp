#include "sim/terrain.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace slide {

double HeightGrid::height(double x, double y) const {
  const double fx = std::clamp((x - origin.x()) / cell, 0.0, nx - 1.0), fy = std::clamp((y - origin.y()) / cell, 0.0, ny - 1.0);
  const int ix = std::min(static_cast<int>(fx), nx - 2 < 0 ? 0 : nx - 2), iy = std::min(static_cast<int>(fy), ny - 2 < 0 ? 0 : ny - 2);
  const int ix1 = std::min(ix + 1, nx - 1), iy1 = std::min(iy + 1, ny - 1);
  const double ax = fx - ix, ay = fy - iy;
  auto at = [&](int i, int j) { return z[static_cast<std::size_t>(j) * nx + i]; };
  return (1 - ay) * ((1 - ax) * at(ix, iy) + ax * at(ix1, iy)) + ay * ((1 - ax) * at(ix, iy1) + ax * at(ix1, iy1));
}

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
  slope_bound = 2 * s;  // bilinear patches can be steeper along diagonals
  z_lo = z.empty() ? 0 : *std::min_element(z.begin(), z.end());
  z_hi = z.empty() ? 0 : *std::max_element(z.begin(), z.end());
}

double Terrain::height(double x, double y) const {
  double z = base_z + (grid.empty() ? 0.0 : grid.height(x, y));
  for (const TerrainWave& w : waves) z += w.amplitude * std::sin(w.kx * x + w.ky * y + w.phase);
  return z;
}

Eigen::Vector2d Terrain::gradient(double x, double y) const {
  Eigen::Vector2d g = grid.empty() ? Eigen::Vector2d::Zero() : grid.gradient(x, y);
  for (const TerrainWave& w : waves) {
    const double c = w.amplitude * std::cos(w.kx * x + w.ky * y + w.phase);
    g += c * Eigen::Vector2d(w.kx, w.ky);
  }
  return g;
}

double Terrain::intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range,
                          uint16_t* hit_semantic) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double best = kInf;
  if (ceiling_z && d.z() > 1e-9) {
    const double t = (*ceiling_z - o.z()) / d.z();
    if (t > 0 && t < max_range) best = t, *hit_semantic = ceiling_semantic;
  }
  auto g = [&](double t) { return o.z() + t * d.z() - height(o.x() + t * d.x(), o.y() + t * d.y()); };
  if (g(0) <= 0) return best;  // start below ground: no hit
  double t_ground = kInf;
  if (waves.empty() && grid.empty()) {
    if (d.z() < -1e-12) t_ground = (base_z - o.z()) / d.z();
  } else {
    // Lipschitz marching (the ray cannot meet the ground closer than g / L), then bisection.
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
    double t0 = 0, t1 = max_range;
    if (d.z() < -1e-12) {
      t1 = std::min(max_range, (zmin - o.z()) / d.z());
      if (o.z() > zmax) t0 = std::max(0.0, (zmax - o.z()) / d.z());
    } else if (o.z() >= zmax) {
      t1 = -1;  // above the highest hill, going up or level: no ground hit
    } else if (d.z() > 1e-12) {
      t1 = std::min(max_range, (zmax - o.z()) / d.z());
    }
    const double lipschitz = std::abs(d.z()) + slope * std::hypot(d.x(), d.y()) + 1e-9;
    double a = t0, ga = g(a);
    while (a < t1) {
      const double b = std::min(a + std::max(ga / lipschitz, 0.1), t1);
      const double gb = g(b);
      if (gb <= 0) {
        double lo = a, hi = b;
        for (int i = 0; i < 30 && hi - lo > 1e-3; ++i) {
          const double m = 0.5 * (lo + hi);
          (g(m) > 0 ? lo : hi) = m;
        }
        t_ground = 0.5 * (lo + hi);
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

}  // namespace slide
