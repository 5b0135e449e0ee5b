#pragma once
// The three object models of the sparse map and the operations every stage shares.
// Vocabulary: in namespace slide itself, not slide::objects, as every area uses it (README).
#include <cstdint>
#include <optional>
#include <variant>

#include "geometry/pose.h"

namespace slide {

enum class Shape { Cuboid, Cylinder, Ellipsoid };

// Box: pose of its centre (x along the length) and full extents (length, width, height).
struct Cuboid {
  Pose pose = Pose::Identity();
  Eigen::Vector3d dims = Eigen::Vector3d::Zero();
};

// Trunk or pole: bottom point, unit axis (pointing up), radius and length along the axis.
struct Cylinder {
  Eigen::Vector3d root = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double radius = 0.0;
  double length = 0.0;
};

// Anything else: centroid, horizontal radius and height.
struct Ellipsoid {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double radius = 0.0;
  double height = 0.0;
};

using ObjectModel = std::variant<Cuboid, Cylinder, Ellipsoid>;

struct Object {
  std::int64_t id = -1;      // track or landmark id; -1 when unassigned
  int class_id = 0;          // key into the ClassTable
  ObjectModel model;
  double confidence = 1.0;
  int num_observations = 1;
  // A box whose length went unseen (a lone end face, a stretch of side) reads two ways: `model`
  // is the reading the front-end settled on, this the box with its length along the other
  // axis. The back-end keeps the reading its landmark agrees with.
  std::optional<Cuboid> other_reading;

  Shape shape() const { return static_cast<Shape>(model.index()); }
  // Centre of the object: cuboid centre, cylinder axis midpoint, ellipsoid centroid.
  Eigen::Vector3d position() const;
  // Full extents of its bounding box in its own frame: cuboid dims, (2r, 2r, length|height).
  Eigen::Vector3d extent() const;
  // True when every number in the model is finite.
  bool isFinite() const;
};

const char* shapeName(Shape s);

// The object as seen from another frame: T maps points of the object's frame into the new one.
Object transformObject(const Pose& T, const Object& o);

}  // namespace slide
