#pragma once
// What surrounds each landmark of a map, for pruning SlideMatch's pair search on large maps:
// the neighbours within a radius (xy offsets, distances, classes), a rotation-invariant
// descriptor of them, and the local yaw vote that turns one landmark's neighbourhood onto
// another's. Two landmarks that are the same object in two maps have neighbourhoods that agree
// up to a yaw (less what either map missed or added); two that are not mostly do not.
#include <cstdint>
#include <vector>

#include "place/landmark.h"

namespace slide::place {

// Rings of the descriptor; each gives the neighbour count and the magnitudes of the first two
// angular harmonics (|sum e^{i theta}|, |sum e^{2 i theta}|), which a yaw does not change.
inline constexpr int kNeighbourhoodRings = 4;
inline constexpr int kNeighbourhoodDims = 3 * kNeighbourhoodRings;
using NeighbourhoodDescriptor = Eigen::Matrix<double, kNeighbourhoodDims, 1>;

class Neighbourhoods {
 public:
  // Neighbours (any class) within `radius` metres, horizontally, of each landmark (a grid over
  // the positions; the landmark itself excluded), at most the `max_neighbours` nearest (memory
  // stays bounded on dense maps). Non-finite positions have no neighbours.
  Neighbourhoods(const std::vector<Landmark>& lms, double radius, std::size_t max_neighbours = 64);

  double radius() const { return radius_; }
  std::size_t size() const { return start_.empty() ? 0 : start_.size() - 1; }
  const NeighbourhoodDescriptor& descriptor(std::size_t i) const { return descriptors_[i]; }

  struct Neighbour {
    float dist;   // metres, horizontal
    float angle;  // radians, direction from the landmark in its map's frame
    int class_id;
  };
  // Neighbours of landmark i sorted by distance.
  const Neighbour* begin(std::size_t i) const { return items_.data() + start_[i]; }
  const Neighbour* end(std::size_t i) const { return items_.data() + start_[i + 1]; }

 private:
  double radius_;
  std::vector<std::uint32_t> start_;
  std::vector<Neighbour> items_;
  std::vector<NeighbourhoodDescriptor> descriptors_;
};

// The yaw that turns landmark j's neighbourhood (map B) onto landmark i's (map A): every pair of
// same-class neighbours at distances within `dist_tol` (and at least min_dist away, where a
// direction means something) votes for the difference of their directions; the votes of the
// best window of three `bin` wide bins, their circular mean and count.
struct LocalYaw {
  double yaw = 0;  // radians, T_a_b's yaw that this pair suggests
  int votes = 0;   // in the best window
  int pairs = 0;   // neighbour pairs that voted at all
  double window_share = 0;  // share of the circle the window covers: chance votes = pairs x this
};
LocalYaw localYaw(const Neighbourhoods& na, std::size_t i, const Neighbourhoods& nb, std::size_t j, double dist_tol,
                  double min_dist, double bin);

}  // namespace slide::place
