#include "simulator/indoor_world.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "simulator/semantic_labels.h"

namespace slide::simulator {

namespace {
io::GroundTruthObject item(int class_id, const Eigen::Vector3d& centroid, double radius, double height) {
  io::GroundTruthObject g;
  g.object.class_id = class_id;
  g.semantic = label::labelOfClassId(class_id);
  g.object.model = Ellipsoid{centroid, radius, height};
  return g;
}

void furnishRoom(World& w, const Eigen::Vector2d& c, double half_w, double half_d, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  // Quadrants keep the cross through the room centre (the robots' way) free.
  std::vector<Eigen::Vector2d> quadrants = {{1, 1}, {-1, 1}, {1, -1}, {-1, -1}};
  std::shuffle(quadrants.begin(), quadrants.end(), rng);
  const int tables = 1 + static_cast<int>(u(rng) * 2.0);
  for (int t = 0; t < tables; ++t) {
    const Eigen::Vector2d q = quadrants[t];
    const double r = 0.5 + 0.2 * u(rng);
    const Eigen::Vector2d tc = c + Eigen::Vector2d(q.x() * 0.5 * half_w, q.y() * 0.5 * half_d);
    w.objects.push_back(item(2, {tc.x(), tc.y(), 0.375}, r, 0.75));
    // A second monitor stands opposite the first (0.5 m apart, side by side): two monitors
    // placed at random angles stood inside one another.
    const int monitors = static_cast<int>(u(rng) * 3.0);
    double first = 0;
    for (int m = 0; m < monitors; ++m) {
      const double drawn = 2 * M_PI * u(rng);  // drawn for each monitor: the rest of the world stays as it was
      const double a = m == 0 ? (first = drawn) : first + M_PI;
      w.objects.push_back(item(3, {tc.x() + 0.25 * std::cos(a), tc.y() + 0.25 * std::sin(a), 0.95}, 0.25, 0.4));
    }
    const int chairs = 2 + static_cast<int>(u(rng) * 3.0);
    const double a0 = 2 * M_PI * u(rng);
    for (int k = 0; k < chairs; ++k) {
      const double a = a0 + 2 * M_PI * k / chairs;
      const Eigen::Vector2d p = tc + (r + 0.4) * Eigen::Vector2d(std::cos(a), std::sin(a));
      w.objects.push_back(item(1, {p.x(), p.y(), 0.45}, 0.28, 0.9));
    }
  }
  // Clutter along the walls in the remaining quadrants.
  for (int k = tables; k < 4; ++k) {
    if (u(rng) < 0.4) continue;
    const Eigen::Vector2d q = quadrants[k];
    const double h = 0.3 + 0.9 * u(rng);
    const Eigen::Vector2d p = c + Eigen::Vector2d(q.x() * (half_w - 0.6), q.y() * (half_d - 0.6));
    w.objects.push_back(item(0, {p.x(), p.y(), 0.5 * h}, 0.2 + 0.25 * u(rng), h));
  }
}
}  // namespace

World makeIndoorWorld(const IndoorParams& p, uint64_t seed) {
  std::mt19937_64 rng(seed);
  World w;
  w.name = "indoor";
  w.terrain.semantic = label::kOtherGround;
  w.terrain.ceiling_z = p.wall_height;
  w.terrain.ceiling_semantic = label::kOtherStructure;

  const int n = p.rooms_per_row;
  const double W = n * p.room_width;
  // y bands: rooms [0, D), corridor [D, D + C), rooms [D + C, 2D + C).
  const double D = p.room_depth, C = p.corridor_width, H = 2 * D + C;
  const double t = p.wall_thickness, h = p.wall_height;
  auto wallX = [&](double x0, double x1, double y) {  // wall along x
    if (x1 - x0 < 0.05) return;
    w.structures.push_back({Cuboid{poseFromXyzYaw(0.5 * (x0 + x1), y, 0.5 * h, 0), {x1 - x0, t, h}}, label::kBuilding});
  };
  auto wallY = [&](double x, double y0, double y1) {  // wall along y
    if (y1 - y0 < 0.05) return;
    w.structures.push_back({Cuboid{poseFromXyzYaw(x, 0.5 * (y0 + y1), 0.5 * h, 0), {t, y1 - y0, h}}, label::kBuilding});
  };
  const double dw = 0.5 * p.door_width;
  // Outer walls.
  wallX(0, W, 0);
  wallX(0, W, H);
  wallY(0, 0, H);
  wallY(W, 0, H);
  // Corridor walls with a door into every room.
  for (double y : {D, D + C})
    for (int i = 0; i < n; ++i) {
      const double xc = (i + 0.5) * p.room_width;
      wallX(i * p.room_width, xc - dw, y);
      wallX(xc + dw, (i + 1) * p.room_width, y);
    }
  // Walls between neighbouring rooms, each with a door in the middle.
  for (int i = 1; i < n; ++i)
    for (double y0 : {0.0, D + C}) {
      const double yc = y0 + 0.5 * D;
      wallY(i * p.room_width, y0, yc - dw);
      wallY(i * p.room_width, yc + dw, y0 + D);
    }
  // Furniture, and a little clutter in the corridor.
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < n; ++i)
    for (double yc : {0.5 * D, D + C + 0.5 * D})
      furnishRoom(w, {(i + 0.5) * p.room_width, yc}, 0.5 * p.room_width, 0.5 * D, rng);
  for (int i = 0; i < n; ++i)
    if (u(rng) < 0.5) {
      const double x = (i + 0.25 + 0.5 * u(rng)) * p.room_width;
      w.objects.push_back(item(0, {x, D + 0.35, 0.4}, 0.25, 0.8));
    }
  // Routes: room centres (two rows) and corridor points in front of each door.
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) * p.room_width;
    w.routes.nodes.emplace_back(x, 0.5 * D);          // 3i: lower room
    w.routes.nodes.emplace_back(x, D + 0.5 * C);      // 3i + 1: corridor
    w.routes.nodes.emplace_back(x, D + C + 0.5 * D);  // 3i + 2: upper room
    w.routes.edges.emplace_back(3 * i, 3 * i + 1);
    w.routes.edges.emplace_back(3 * i + 1, 3 * i + 2);
    if (i + 1 < n)
      for (int k = 0; k < 3; ++k) w.routes.edges.emplace_back(3 * i + k, 3 * (i + 1) + k);
  }
  w.bounds = Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(W + 1, H + 1));
  w.renumber();
  return w;
}

}  // namespace slide::simulator
