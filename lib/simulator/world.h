#pragma once
// A simulated world: ground-truth objects (the landmarks a map should contain), scenery that
// only occludes and returns points (walls, tree crowns, clutter), the ground, and a graph of
// drivable routes robots follow. Every world is generated from a seed and is reproducible.
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "io/ground_truth_objects.h"
#include "simulator/terrain.h"

namespace slide::simulator {

// Scenery: a shape with a per-point label and no instance (instance id 0).
struct Structure {
  ObjectModel model;
  uint16_t semantic = label::kOtherStructure;
};

// Nodes (x, y) joined by straight edges that are free of obstacles (with clearance).
struct RouteGraph {
  std::vector<Eigen::Vector2d> nodes;
  std::vector<std::pair<int, int>> edges;
  std::vector<std::vector<int>> neighbours() const;
};

struct World {
  std::string name;
  std::vector<io::GroundTruthObject> objects;  // objects[i].object.id == i + 1 == instance id
  std::vector<Structure> structures;
  Terrain terrain;
  RouteGraph routes;
  Eigen::AlignedBox2d bounds;

  // Renumbers object ids to index + 1 (call after adding or removing objects).
  void renumber();
  // Removes every object and structure whose footprint comes within `clearance` metres of a
  // segment of the polyline (keeps structures whose semantic is in `keep`), unless all of it
  // stands higher than `headroom` above the ground under it (a crown over the path of a robot
  // that passes below it).
  void clearAlong(const std::vector<Eigen::Vector2d>& polyline, double clearance,
                  const std::vector<uint16_t>& keep_semantic = {},
                  double headroom = std::numeric_limits<double>::infinity());
};

// Horizontal distance from point p to segment ab.
double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b);
// Horizontal footprint radius of a model around its centre (bounding circle).
double footprintRadius(const ObjectModel& m);
// Horizontal centre of a model's footprint.
Eigen::Vector2d footprintCentre(const ObjectModel& m);

}  // namespace slide::simulator
