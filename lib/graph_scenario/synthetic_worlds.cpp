// The indoor, urban and forest scenarios of the back-end benchmark.
#include <algorithm>
#include <cmath>
#include <functional>

#include "graph_scenario/scenario.h"

namespace slide::graph_scenario {

namespace {
double uniform(std::mt19937& rng, double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }

double distanceToPath(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& wp) {
  double best = 1e18;
  for (std::size_t i = 1; i < wp.size(); ++i) {
    const Eigen::Vector2d d = wp[i] - wp[i - 1];
    const double t = std::clamp((p - wp[i - 1]).dot(d) / std::max(1e-12, d.squaredNorm()), 0.0, 1.0);
    best = std::min(best, (p - (wp[i - 1] + t * d)).norm());
  }
  return best;
}

// Rejection-samples `count` landmark positions in [lo, hi] whose distance to the path lies in
// [min_path, max_path] and that keep `separation` from every earlier one; make() builds each.
void scatter(std::vector<Object>& out, int count, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
             const std::vector<Eigen::Vector2d>& path, double min_path, double max_path, double separation,
             std::mt19937& rng, const std::function<Object(const Eigen::Vector2d&, const Eigen::Vector2d&)>& make) {
  int placed = 0;
  for (int attempt = 0; placed < count && attempt < count * 2000; ++attempt) {
    const Eigen::Vector2d p(uniform(rng, lo.x(), hi.x()), uniform(rng, lo.y(), hi.y()));
    const double d = distanceToPath(p, path);
    if (d < min_path || d > max_path) continue;
    bool clear = true;
    for (const Object& o : out) clear = clear && (o.position().head<2>() - p).norm() >= separation;
    if (!clear) continue;
    // Direction of the nearest path segment, for objects aligned with the street.
    Eigen::Vector2d dir = Eigen::Vector2d::UnitX();
    double best = 1e18;
    for (std::size_t i = 1; i < path.size(); ++i) {
      const double di = distanceToPath(p, {path[i - 1], path[i]});
      if (di < best && (path[i] - path[i - 1]).norm() > 0) {
        best = di;
        dir = (path[i] - path[i - 1]).normalized();
      }
    }
    Object o = make(p, dir);
    o.id = static_cast<std::int64_t>(out.size());
    out.push_back(o);
    ++placed;
  }
}

Object ellipsoid(int class_id, const Eigen::Vector3d& c, double radius, double height) {
  Object o;
  o.class_id = class_id;
  o.model = Ellipsoid{c, radius, height};
  return o;
}

Object trunk(int class_id, const Eigen::Vector2d& p, double radius, double length, std::mt19937& rng) {
  Object o;
  o.class_id = class_id;
  const Eigen::Vector3d axis = Eigen::Vector3d(uniform(rng, -0.03, 0.03), uniform(rng, -0.03, 0.03), 1.0).normalized();
  o.model = Cylinder{Eigen::Vector3d(p.x(), p.y(), 0.0), axis, radius, length};
  return o;
}

GraphScenario finish(const std::string& name, std::vector<Object> landmarks, const std::vector<Pose>& path,
                const ScenarioNoise& noise, std::mt19937& rng) {
  GraphScenario s;
  s.name = name;
  s.noise = noise;
  s.landmarks = std::move(landmarks);
  s.robots.push_back(simulateRobot(0, path, s.landmarks, noise, rng));
  return s;
}
}  // namespace

GraphScenario makeIndoorScenario(std::uint32_t seed) {
  std::mt19937 rng(seed);
  const std::vector<Eigen::Vector2d> lap = {{2, 2}, {8, 2}, {8, 18}, {2, 18}, {2, 2}, {8, 2}, {8, 18}, {5, 18}};
  std::vector<Object> lms;
  scatter(lms, 70, {0.3, 0.3}, {9.7, 19.7}, lap, 0.7, 1e9, 1.3, rng,
          [&](const Eigen::Vector2d& p, const Eigen::Vector2d&) {
            const int kind = static_cast<int>(uniform(rng, 0, 4));
            if (kind == 0) return ellipsoid(1, {p.x(), p.y(), 0.45}, uniform(rng, 0.25, 0.35), 0.9);  // chair
            if (kind == 1) return ellipsoid(2, {p.x(), p.y(), 0.37}, uniform(rng, 0.5, 0.9), 0.75);   // table
            if (kind == 2) return ellipsoid(3, {p.x(), p.y(), 1.0}, uniform(rng, 0.2, 0.3), 0.4);     // monitor
            return ellipsoid(0, {p.x(), p.y(), 0.5}, uniform(rng, 0.2, 0.6), uniform(rng, 0.3, 1.2));
          });
  ScenarioNoise n;
  n.range = 4.0;
  return finish("indoor", std::move(lms), pathAlongWaypoints(lap, 150, 0.0), n, rng);
}

GraphScenario makeUrbanScenario(std::uint32_t seed) {
  std::mt19937 rng(seed);
  // A 150 m block driven around once (600 m), then its first street again (115 m): 715 m.
  const std::vector<Eigen::Vector2d> route = {{25, 25}, {175, 25}, {175, 175}, {25, 175}, {25, 25}, {140, 25}};
  std::vector<Object> lms;
  scatter(lms, 250, {0, 0}, {200, 200}, route, 3.5, 14.0, 4.0, rng,
          [&](const Eigen::Vector2d& p, const Eigen::Vector2d& dir) {
            const double u = uniform(rng, 0, 1);
            Object o;
            if (u < 0.45) {  // parked car along the street
              o.class_id = 10;
              Pose T = poseFromXyzYaw(p.x(), p.y(), 0.75, std::atan2(dir.y(), dir.x()));
              o.model = Cuboid{T, Eigen::Vector3d(uniform(rng, 3.8, 5.0), uniform(rng, 1.7, 2.0), uniform(rng, 1.4, 1.7))};
            } else if (u < 0.8) {
              o = trunk(80, p, uniform(rng, 0.08, 0.2), uniform(rng, 3.0, 8.0), rng);  // pole
            } else {
              o = ellipsoid(0, {p.x(), p.y(), 0.6}, uniform(rng, 0.3, 1.0), uniform(rng, 0.6, 1.5));
            }
            return o;
          });
  ScenarioNoise n;
  n.range = 15.0;
  return finish("urban", std::move(lms), pathAlongWaypoints(route, 300, 0.0), n, rng);
}

namespace {
// The forest's route: loop A up the shared edge x = 200 and back round the west; loop B round
// the east and back down the shared edge: 2 x 715 m = 1430 m, starting and ending at (200, 100).
std::vector<Eigen::Vector2d> forestRoute(double x_offset) {
  const double w = 150, h = 207.5, x0 = 200 + x_offset, y0 = 100;
  return {{x0, y0},     {x0, y0 + h},     {x0 - w, y0 + h}, {x0 - w, y0}, {x0, y0},
          {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h},     {x0, y0}};
}

std::vector<Object> forestTrunks(std::mt19937& rng) {
  std::vector<Object> lms;
  scatter(lms, 860, {0, 0}, {400, 400}, forestRoute(0), 2.0, 14.5, 2.5, rng,
          [&](const Eigen::Vector2d& p, const Eigen::Vector2d&) {
            return trunk(71, p, uniform(rng, 0.1, 0.4), uniform(rng, 8.0, 15.0), rng);
          });
  return lms;
}

GraphScenario forestScenario(const std::string& name, std::vector<Object> lms, const std::vector<Pose>& path, std::mt19937& rng) {
  ScenarioNoise n;
  n.range = 15.0;
  return finish(name, std::move(lms), path, n, rng);
}
}  // namespace

GraphScenario makeForestScenario(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<Object> lms = forestTrunks(rng);
  return forestScenario("forest", std::move(lms), pathAlongWaypoints(forestRoute(0), 1000, 0.0), rng);
}

namespace {
constexpr double kForestSpacing = 1430.0 / 999.0;  // the forest's key-pose spacing
constexpr double kTileStep = 400.0;                 // tiles sit this far apart in x

// `tiles` copies of the forest tile side by side and their routes driven one after the other
// (each route's end joined to the next one's start along y = 100 m).
void chainTiles(int tiles, std::mt19937& rng, std::vector<Eigen::Vector2d>& route, std::vector<Object>& lms) {
  const std::vector<Object> tile = forestTrunks(rng);
  for (int t = 0; t < tiles; ++t) {
    const std::vector<Eigen::Vector2d> r = forestRoute(kTileStep * t);
    route.insert(route.end(), r.begin(), r.end());
    for (Object o : tile) {
      std::get<Cylinder>(o.model).root.x() += kTileStep * t;
      o.id = static_cast<std::int64_t>(lms.size());
      lms.push_back(o);
    }
  }
}

double routeLength(const std::vector<Eigen::Vector2d>& route) {
  double length = 0;
  for (std::size_t i = 1; i < route.size(); ++i) length += (route[i] - route[i - 1]).norm();
  return length;
}
}  // namespace

GraphScenario makeForestChainScenario(int num_keyposes, std::uint32_t seed) {
  std::mt19937 rng(seed);
  const double tile_length = 1430.0 + kTileStep;  // one route and the road to the next tile's start
  const int tiles = std::max(1, static_cast<int>(std::ceil(num_keyposes * kForestSpacing / tile_length)) + 1);
  std::vector<Eigen::Vector2d> route;
  std::vector<Object> lms;
  chainTiles(tiles, rng, route, lms);
  std::vector<Pose> path =
      pathAlongWaypoints(route, static_cast<int>(std::lround(routeLength(route) / kForestSpacing)) + 1, 0.0);
  path.resize(std::min<std::size_t>(path.size(), static_cast<std::size_t>(std::max(2, num_keyposes))));
  return forestScenario("forest_chain", std::move(lms), path, rng);
}

GraphScenario makeForestReturnScenario(int num_keyposes, std::uint32_t seed) {
  std::mt19937 rng(seed);
  const int n = std::max(2, num_keyposes);
  // Out through `tiles` tiles, back along y = 100 m from the last tile's start to the first's.
  auto length = [](int tiles) { return tiles * 1430.0 + 2 * (tiles - 1) * kTileStep; };
  int tiles = 1;
  while (length(tiles) < (n - 1) * kForestSpacing - 1e-6) ++tiles;
  std::vector<Eigen::Vector2d> route;
  std::vector<Object> lms;
  chainTiles(tiles, rng, route, lms);
  if (tiles > 1) route.push_back(forestRoute(0).front());
  return forestScenario("forest_return", std::move(lms), pathAlongWaypoints(route, n, 0.0), rng);
}

}  // namespace slide::graph_scenario
