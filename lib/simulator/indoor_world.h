#pragma once
// Indoor worlds: an office floor with a corridor between two rows of rooms. Walls (building
// scenery) have doors; rooms hold tables (2), chairs (1), monitors (3) and clutter (other 0),
// all ellipsoids; floor and ceiling close the space. Robots move between room centres
// through the doors and along the corridor.
#include "simulator/world.h"

namespace slide::simulator {

struct IndoorParams {
  int rooms_per_row = 6;
  double room_width = 6.0, room_depth = 6.0, corridor_width = 3.0;  // metres
  double wall_height = 2.8, wall_thickness = 0.15, door_width = 1.2;
};

World makeIndoorWorld(const IndoorParams& params, uint64_t seed);

}  // namespace slide::simulator
