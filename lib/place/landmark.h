#pragma once
// The view of an object map that place recognition works on: centre, extents, class and the
// object's index in its map. Built once per query; everything in lib/place indexes into it.
#include <cstdint>
#include <string>
#include <vector>

#include "objects/object_map.h"

namespace slide::place {

struct Landmark {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();     // centre; a cylinder's foot
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // bounding-box extents; zero = unknown
  int class_id = 0;
  std::size_t index = 0;  // position in the source ObjectMap
  Shape shape = Shape::Ellipsoid;
};

// Landmarks of the finite objects of `map` (non-finite ones are left out), at their centres;
// cylinders at their foot (the axis's lowest point).
std::vector<Landmark> landmarksOf(const ObjectMap& map);

// Why this set cannot be matched (empty string when usable): fewer than `min_count`
// landmarks, non-finite values, or all landmarks at one point. `name` labels the message.
std::string unusableReason(const std::vector<Landmark>& lms, std::size_t min_count, const std::string& name);

// Sizes agree when either is unknown (all zero) or the extent difference norm is within tol;
// for the horizontal extents the order does not matter (length and width may swap).
bool sizesAgree(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol);

// The share of landmarks whose class the other set also holds, the lower of the two sets'
// shares (1 when both are empty).
double sharedClassShare(const std::vector<Landmark>& a, const std::vector<Landmark>& b);

// The landmarks with each class replaced by its shape family (negative ids: -1 cuboid, -2
// cylinder, -3 ellipsoid), for robots whose detectors name different classes.
std::vector<Landmark> byShapeFamily(std::vector<Landmark> lms);

// Centroid of the positions (zero for an empty set).
Eigen::Vector3d centroidOf(const std::vector<Landmark>& lms);

}  // namespace slide::place
