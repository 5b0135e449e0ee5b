#include "simulator/world.h"

#include <algorithm>
#include <cmath>

namespace slide::simulator {

std::vector<std::vector<int>> RouteGraph::neighbours() const {
  std::vector<std::vector<int>> n(nodes.size());
  for (const auto& [a, b] : edges) {
    n[a].push_back(b);
    n[b].push_back(a);
  }
  return n;
}

void World::renumber() {
  for (std::size_t i = 0; i < objects.size(); ++i) objects[i].object.id = static_cast<std::int64_t>(i + 1);
}

double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

double footprintRadius(const ObjectModel& m) {
  if (const auto* c = std::get_if<Cuboid>(&m)) return 0.5 * std::hypot(c->dims.x(), c->dims.y());
  if (const auto* c = std::get_if<Cylinder>(&m)) return c->radius + 0.5 * c->length * c->axis.head<2>().norm();
  return std::get<Ellipsoid>(m).radius;
}

Eigen::Vector2d footprintCentre(const ObjectModel& m) {
  if (const auto* c = std::get_if<Cuboid>(&m)) return c->pose.translation().head<2>();
  if (const auto* c = std::get_if<Cylinder>(&m)) return (c->root + 0.5 * c->length * c->axis).head<2>();
  return std::get<Ellipsoid>(m).centroid.head<2>();
}

namespace {
// Height of a model's lowest point.
double bottomOf(const ObjectModel& m) {
  if (const auto* c = std::get_if<Cuboid>(&m))
    return c->pose.translation().z() - 0.5 * (c->pose.linear().cwiseAbs() * c->dims).z();
  if (const auto* c = std::get_if<Cylinder>(&m)) return std::min(c->root.z(), c->root.z() + c->length * c->axis.z());
  const auto& e = std::get<Ellipsoid>(m);
  return e.centroid.z() - 0.5 * e.height;
}

bool nearPolyline(const ObjectModel& m, const std::vector<Eigen::Vector2d>& line, double clearance) {
  const Eigen::Vector2d c = footprintCentre(m);
  const double r = footprintRadius(m) + clearance;
  for (std::size_t i = 0; i + 1 < line.size(); ++i)
    if (distanceToSegment(c, line[i], line[i + 1]) < r) return true;
  return line.size() == 1 && (line[0] - c).norm() < r;
}
}  // namespace

void World::clearAlong(const std::vector<Eigen::Vector2d>& polyline, double clearance,
                       const std::vector<uint16_t>& keep_semantic, double headroom) {
  auto inTheWay = [&](const ObjectModel& m) {
    const Eigen::Vector2d c = footprintCentre(m);
    return bottomOf(m) - terrain.height(c.x(), c.y()) <= headroom && nearPolyline(m, polyline, clearance);
  };
  objects.erase(std::remove_if(objects.begin(), objects.end(),
                               [&](const io::GroundTruthObject& g) { return inTheWay(g.object.model); }),
                objects.end());
  structures.erase(std::remove_if(structures.begin(), structures.end(),
                                  [&](const Structure& s) {
                                    if (std::find(keep_semantic.begin(), keep_semantic.end(), s.semantic) !=
                                        keep_semantic.end())
                                      return false;
                                    return inTheWay(s.model);
                                  }),
                   structures.end());
  renumber();
}

}  // namespace slide::simulator
