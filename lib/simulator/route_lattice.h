#pragma once
// A jittered square lattice of route nodes with 4-neighbour edges, inset from the bounds.
#include <random>

#include "simulator/world.h"

namespace slide::simulator {

RouteGraph routeLattice(const Eigen::AlignedBox2d& bounds, double spacing, double jitter, std::mt19937_64& rng);

}  // namespace slide::simulator
