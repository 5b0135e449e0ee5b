#pragma once
// The visible faces of an object model as seen in a View: cuboid faces turned towards the
// viewer, a cylinder's body and top cap, an ellipsoid's outline; all as picture-plane polygons.
#include <vector>

#include "objects/object.h"
#include "plot/view.h"

namespace slide::plot {

struct Facet {
  std::vector<Eigen::Vector2d> uv;  // polygon in picture-plane metres
  double shade = 1.0;               // 1 = the class colour; smaller is darker (sides)
};

struct ObjectFacets {
  std::vector<Facet> facets;  // draw in order
  std::vector<Eigen::Vector2d> silhouette;  // convex outline of the whole object
  double depth = 0;           // of the object's centre; draw far objects first
};

ObjectFacets objectFacets(const Object& o, const View& view);

// Convex hull (counter-clockwise) of 2D points; Andrew's monotone chain.
std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> pts);

}  // namespace slide::plot
