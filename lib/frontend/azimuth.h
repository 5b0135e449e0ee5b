#pragma once
// Fast azimuth: atan2(y, x) in [-pi, pi] by the octant's symmetry and the polynomial of
// Abramowitz & Stegun 4.4.49 for atan on [0, 1] (error 2e-8 rad, float rounding aside):
// several times cheaper than std::atan2, far finer than the 0.1-0.4 deg azimuth step of a
// spinning LiDAR or any angular bin of the segmenters. (0, 0) gives 0; inputs must be finite.
#include <algorithm>
#include <cmath>

namespace slide::frontend {

inline float azimuthOf(float y, float x) {
  const float ax = std::abs(x), ay = std::abs(y), hi = std::max(ax, ay);
  if (hi == 0) return 0;
  const float a = std::min(ax, ay) / hi, s = a * a;
  float r = a * (1 + s * (-0.3333314528f + s * (0.1999355085f + s * (-0.1420889944f + s * (0.1065626393f +
                 s * (-0.0752896400f + s * (0.0429096138f + s * (-0.0161657367f + s * 0.0028662257f))))))));
  if (ay > ax) r = float(M_PI_2) - r;
  if (x < 0) r = float(M_PI) - r;
  return y < 0 ? -r : r;
}

}  // namespace slide::frontend
