#pragma once
// Colours for robots (trajectories, map outlines) that stay apart from the class colours.
#include "plot/canvas.h"

namespace slide::plot {

Rgb robotColour(int robot);
// c scaled towards black (f < 1) or white (f > 1, up to 2).
Rgb shadeColour(Rgb c, double f);

// A perceptually ordered colour ramp (dark blue - teal - yellow, like viridis) for t in 0..1.
Rgb rampColour(double t);

}  // namespace slide::plot
