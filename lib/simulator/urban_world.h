#pragma once
// Urban parking-lot worlds: cars (cuboids, class car 10) parked in double rows with realistic
// sizes and small yaw errors, light poles (pole 80) and trees (trunk 71) on the row islands,
// some clutter (other 0), building walls around the lot and a few cars moving on the road
// outside it. Robots drive the aisles (route graph: aisles x three cross lanes).
#include "simulator/world.h"

namespace slide::simulator {

struct UrbanParams {
  int double_rows = 4;        // back-to-back parking rows
  int bays_per_block = 10;    // bays per row on each side of the middle cross lane
  double bay_width = 2.6, bay_depth = 5.2, aisle = 7.0;  // metres
  double occupancy = 0.75;    // share of bays holding a car
  int moving_cars = 4;
};

World makeUrbanWorld(const UrbanParams& params, uint64_t seed);

}  // namespace slide::simulator
