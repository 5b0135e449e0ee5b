#pragma once
// A dense per-class bucket grid over the xy positions of a landmark set: constant-time
// "is there a landmark of this class, with agreeing size, within r of (x, y)?" queries for
// scoring many candidate transforms.
#include <map>

#include "place/landmark.h"

namespace slide::place {

class ClassGrid {
 public:
  // `cell` should be about the query radius; positions are used as given (xy only). The grid
  // refers to `lms`, which must outlive it.
  ClassGrid(const std::vector<Landmark>& lms, double cell);

  // Index of the nearest landmark of class `class_id` within r (xy) of p whose size agrees
  // with `size` (tolerance size_tol), or -1.
  long nearestWithin(int class_id, double x, double y, double r, const Eigen::Vector3d& size, double size_tol) const;

 private:
  struct Buckets {
    std::vector<std::uint32_t> start;  // CSR over cells, size nx*ny+1
    std::vector<std::uint32_t> items;  // landmark indices
  };
  const std::vector<Landmark>& lms_;
  double cell_, x0_, y0_;
  long nx_ = 0, ny_ = 0;
  std::map<int, Buckets> classes_;
};

}  // namespace slide::place
