#pragma once
// Descriptor of a Delaunay triangle: its vertex-to-centroid distances sorted ascending, and the
// vertices (and their classes) in that order, so that two matching descriptors give three
// vertex correspondences.
#include <array>
#include <vector>

#include "place/delaunay.h"
#include "place/landmark.h"

namespace slide::place {

struct SimplexDescriptor {
  Eigen::Vector3d distances = Eigen::Vector3d::Zero();  // ascending, metres (xy)
  Triangle vertices{};                                  // landmark indices in the same order
  std::array<int, 3> classes{};
};

// One descriptor per triangle (ties broken by class, then landmark index).
std::vector<SimplexDescriptor> describeTriangles(const std::vector<Landmark>& lms, const std::vector<Triangle>& tris);

}  // namespace slide::place
