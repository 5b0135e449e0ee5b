#include "simulator/route_lattice.h"

#include <cmath>

namespace slide::simulator {

RouteGraph routeLattice(const Eigen::AlignedBox2d& bounds, double spacing, double jitter, std::mt19937_64& rng) {
  RouteGraph g;
  const Eigen::Vector2d lo = bounds.min() + Eigen::Vector2d::Constant(0.5 * spacing);
  const Eigen::Vector2d size = bounds.max() - bounds.min() - Eigen::Vector2d::Constant(spacing);
  const int nx = std::max(2, static_cast<int>(size.x() / spacing) + 1);
  const int ny = std::max(2, static_cast<int>(size.y() / spacing) + 1);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) g.nodes.push_back(lo + Eigen::Vector2d(i * size.x() / (nx - 1) + u(rng), j * size.y() / (ny - 1) + u(rng)));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int k = j * nx + i;
      if (i + 1 < nx) g.edges.emplace_back(k, k + 1);
      if (j + 1 < ny) g.edges.emplace_back(k, k + nx);
    }
  return g;
}

}  // namespace slide::simulator
