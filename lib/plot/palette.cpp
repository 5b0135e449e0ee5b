#include "plot/palette.h"

#include <algorithm>
#include <array>

namespace slide {

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

}  // namespace slide
