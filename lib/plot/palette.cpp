#include "plot/palette.h"

#include <algorithm>
#include <array>

namespace slide::plot {

Rgb robotColour(int robot) {
  static const std::array<Rgb, 8> kRobots{{{0, 90, 200},
                                           {220, 0, 130},
                                           {0, 160, 150},
                                           {240, 150, 0},
                                           {120, 60, 190},
                                           {110, 110, 110},
                                           {150, 200, 0},
                                           {0, 190, 240}}};
  return kRobots[static_cast<std::size_t>(std::abs(robot)) % kRobots.size()];
}

Rgb shadeColour(Rgb c, double f) {
  auto ch = [&](int v) {
    const double x = f <= 1 ? v * f : v + (255 - v) * (f - 1);
    return std::clamp(static_cast<int>(x + 0.5), 0, 255);
  };
  return {ch(c.r), ch(c.g), ch(c.b)};
}

Rgb rampColour(double t) {
  static const std::array<Rgb, 6> kStops{{{68, 1, 84}, {65, 68, 135}, {42, 120, 142}, {34, 168, 132}, {122, 209, 81},
                                          {253, 231, 37}}};
  if (!(t > 0)) t = 0;  // also NaN
  if (t > 1) t = 1;
  const double x = t * (kStops.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), kStops.size() - 2);
  const double f = x - i;
  auto mix = [&](int a, int b) { return static_cast<int>(a + (b - a) * f + 0.5); };
  return {mix(kStops[i].r, kStops[i + 1].r), mix(kStops[i].g, kStops[i + 1].g), mix(kStops[i].b, kStops[i + 1].b)};
}

}  // namespace slide::plot
