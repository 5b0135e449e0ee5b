#pragma once
// Where a scan saw through: cells of a car body's height band that a line of sight crosses on
// its way to a farther return. A car's body is solid end to end between about 0.3 and 0.9 m
// above the ground, so a box completed over such cells (grown the wrong way from a partly seen
// car) stands where the sensor saw nothing. Lines of sight to the ground beyond an object cross
// that band too: the ground seen past a car's end says the end is there.
#include <vector>

#include <Eigen/Core>

#include "frontend/instance.h"

namespace slide::frontend {

struct FreeSpaceParams {
  double cell = 0.2;        // metres: the cells' side (0: off)
  double band_low = 0.3;    // the height band, metres above the ground under the object
  double band_high = 0.9;
  double margin = 0.3;      // a line of sight is free up to this short of its return (range noise, edges)
  double azimuth_step_deg = 0.5;  // lines of sight taken this far apart in azimuth (at most)
};

class FreeSpace {
 public:
  // `cloud`: every return of the scan, sensor frame (sensor at the origin); must outlive this.
  FreeSpace(const Cloud& cloud, FreeSpaceParams params);

  // The centres of the free cells within `reach` metres of the points `cluster` (indices into the
  // cloud), whose ground lies at height `ground_z`: z = the band's middle.
  Cloud near(const std::vector<int>& cluster, float ground_z, double reach) const;

 private:
  const Cloud& cloud_;
  FreeSpaceParams p_;
  int bins_ = 0;
  std::vector<int> start_;  // the returns of azimuth bin b: [start_[b], start_[b + 1]) of ...
  std::vector<float> range_, slope_;  // ... their horizontal ranges and z / range
};

}  // namespace slide::frontend
