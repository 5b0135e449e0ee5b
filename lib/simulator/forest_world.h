#pragma once
// Forest worlds: trunks (cylinders, class trunk 71) with crowns (vegetation scenery) and some
// undergrowth on uneven terrain. Stem layouts are procedural (clustered, Thomas-like process)
// or real mapped plots from forest_inventory (tiled to cover the requested area).
#include <string>

#include "simulator/world.h"

namespace slide::simulator {

struct ForestParams {
  // "procedural", or a plot of forest_inventory: "longleaf", "finpines", "spruces".
  std::string layout = "procedural";
  std::string inventory_dir;        // folder of the inventory CSVs (default SLIDE_DATA_DIR/forest_inventory)
  double side = 150.0;              // square world side, metres
  int num_trees = 860;              // procedural: number of stems
  double cluster_fraction = 0.6;    // procedural: share of stems in clusters (rest uniform)
  double cluster_sigma = 6.0;       // procedural: cluster spread, metres
  double dbh_mean = 0.32, dbh_sd = 0.12;  // procedural: diameter at breast height, metres
  double max_lean_deg = 8.0;
  double terrain_amplitude = 1.0;   // metres
  bool crowns = true;
  int bushes = 150;                 // undergrowth ellipsoids (vegetation scenery)
  double route_spacing = 20.0;      // spacing of the route lattice, metres
};

World makeForestWorld(const ForestParams& params, uint64_t seed);

}  // namespace slide::simulator
