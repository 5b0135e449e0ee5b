#include "simulator/kitti_world.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <fstream>
#include <random>
#include <sstream>

#include "io/io_error.h"
#include "simulator/semantic_labels.h"

namespace slide::simulator {

namespace {
constexpr double kSensorHeight = 1.73;

// Ground heights on a 4 m grid: the height under the nearest trajectory pose.
HeightGrid groundGrid(const std::vector<Pose>& poses, const Eigen::AlignedBox2d& bounds) {
  HeightGrid g;
  g.cell = 4.0;
  g.origin = bounds.min();
  g.nx = static_cast<int>(std::ceil(bounds.sizes().x() / g.cell)) + 1;
  g.ny = static_cast<int>(std::ceil(bounds.sizes().y() / g.cell)) + 1;
  std::vector<Eigen::Vector3d> samples;
  for (std::size_t i = 0; i < poses.size(); i += 5) samples.push_back(poses[i].translation());
  // Bucket samples in 20 m cells so each grid node checks only nearby ones.
  const double bc = 20.0;
  const int bx = static_cast<int>(std::ceil(bounds.sizes().x() / bc)) + 1, by = static_cast<int>(std::ceil(bounds.sizes().y() / bc)) + 1;
  std::vector<std::vector<int>> buckets(static_cast<std::size_t>(bx) * by);
  auto bucketOf = [&](double x, double y, int& ix, int& iy) {
    ix = std::clamp(static_cast<int>((x - g.origin.x()) / bc), 0, bx - 1);
    iy = std::clamp(static_cast<int>((y - g.origin.y()) / bc), 0, by - 1);
  };
  for (std::size_t k = 0; k < samples.size(); ++k) {
    int ix, iy;
    bucketOf(samples[k].x(), samples[k].y(), ix, iy);
    buckets[static_cast<std::size_t>(iy) * bx + ix].push_back(static_cast<int>(k));
  }
  g.z.resize(static_cast<std::size_t>(g.nx) * g.ny);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const Eigen::Vector2d p = g.origin + g.cell * Eigen::Vector2d(i, j);
      int ix, iy;
      bucketOf(p.x(), p.y(), ix, iy);
      double best = std::numeric_limits<double>::infinity(), z = samples.front().z();
      for (int r = 0; r < std::max(bx, by) && !std::isfinite(best); ++r) {
        for (int yy = iy - r; yy <= iy + r; ++yy)
          for (int xx = ix - r; xx <= ix + r; ++xx) {
            if (xx < 0 || yy < 0 || xx >= bx || yy >= by) continue;
            if (std::max(std::abs(xx - ix), std::abs(yy - iy)) != r) continue;
            for (int k : buckets[static_cast<std::size_t>(yy) * bx + xx]) {
              const double d = (samples[k].head<2>() - p).squaredNorm();
              if (d < best) best = d, z = samples[k].z();
            }
          }
      }
      g.z[static_cast<std::size_t>(j) * g.nx + i] = z - kSensorHeight;
    }
  g.finish();
  return g;
}

double distanceToPath(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& path) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < path.size(); ++i) best = std::min(best, distanceToSegment(p, path[i], path[i + 1]));
  return best;
}
}  // namespace

std::vector<Eigen::Vector2d> readPoleMap(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw io::IoError(path, "cannot open file");
  std::string line;
  std::getline(in, line);
  std::vector<Eigen::Vector2d> poles;
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream s(line);
    double x, y;
    if (!(s >> x >> y)) throw io::IoError(path, "line " + std::to_string(n) + ": expected x,y");
    poles.emplace_back(x, y);
  }
  return poles;
}

World makeKittiWorld(const std::vector<Pose>& lidar_poses, const std::string& pole_csv, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> n01(0, 1);
  World w;
  w.name = "kitti";
  w.terrain.semantic = label::kRoad;
  Eigen::AlignedBox2d box;
  std::vector<Eigen::Vector2d> path;
  for (std::size_t i = 0; i < lidar_poses.size(); i += 2) path.push_back(lidar_poses[i].translation().head<2>());
  for (const auto& p : path) box.extend(p);
  const std::vector<Eigen::Vector2d> poles = readPoleMap(pole_csv);
  for (const auto& p : poles) box.extend(p);
  box.min() -= Eigen::Vector2d::Constant(60);
  box.max() += Eigen::Vector2d::Constant(60);
  w.bounds = box;
  w.terrain.grid = groundGrid(lidar_poses, box);

  for (const auto& p : poles) {
    const double zg = w.terrain.height(p.x(), p.y());
    io::GroundTruthObject g;
    if (u(rng) < 0.55) {
      g.object.class_id = 80;
      g.semantic = label::kPole;
      g.object.model = Cylinder{{p.x(), p.y(), zg - 0.2}, Eigen::Vector3d::UnitZ(), 0.07 + 0.06 * u(rng), 4.5 + 3.5 * u(rng)};
    } else {
      const double h = 6 + 5 * u(rng);
      g.object.class_id = 71;
      g.semantic = label::kTrunk;
      g.object.model = Cylinder{{p.x(), p.y(), zg - 0.2}, Eigen::Vector3d::UnitZ(), 0.12 + 0.15 * u(rng), 0.55 * h};
      w.structures.push_back({Ellipsoid{{p.x(), p.y(), zg + 0.75 * h}, 1.5 + 1.5 * u(rng), 0.5 * h}, label::kVegetation});
    }
    w.objects.push_back(g);
  }
  // Parked cars along the kerb and walls further out, sampled along the trajectory.
  std::vector<Eigen::Vector2d> placed;
  double next_car = 5, next_wall = 10, s = 0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const Eigen::Vector2d d = path[i] - path[i - 1];
    s += d.norm();
    if (d.norm() < 1e-3) continue;
    const Eigen::Vector2d f = d.normalized(), left(-f.y(), f.x());
    const double yaw = std::atan2(f.y(), f.x());
    if (s > next_car) {
      next_car = s + 6 + 14 * u(rng);
      const double side = u(rng) < 0.5 ? 1 : -1;
      const Eigen::Vector2d c = path[i] + side * (4.0 + 1.0 * u(rng)) * left;
      bool ok = distanceToPath(c, path) > 3.2;
      for (const auto& q : placed) ok = ok && (q - c).norm() > 5.5;
      for (const auto& q : poles) ok = ok && (q - c).norm() > 3.0;
      if (ok) {
        const double L = 3.9 + 1.0 * u(rng), W = 1.7 + 0.25 * u(rng), H = 1.4 + 0.3 * u(rng);
        io::GroundTruthObject g;
        g.object.class_id = 10;
        g.semantic = label::kCar;
        g.object.model = Cuboid{poseFromXyzYaw(c.x(), c.y(), w.terrain.height(c.x(), c.y()) + 0.5 * H,
                                               yaw + (u(rng) < 0.8 ? 0 : M_PI) + 0.05 * n01(rng)),
                                {L, W, H}};
        w.objects.push_back(g);
        placed.push_back(c);
      }
    }
    if (s > next_wall) {
      next_wall = s + 15 + 30 * u(rng);
      const double side = u(rng) < 0.5 ? 1 : -1;
      const double len = 10 + 20 * u(rng), depth = 8, h = 6 + 8 * u(rng);
      const Eigen::Vector2d c = path[i] + side * (12 + 4 * u(rng) + 0.5 * depth) * left;
      bool ok = true;
      for (double a : {-0.5, 0.0, 0.5})
        for (double b : {-0.5, 0.0, 0.5}) ok = ok && distanceToPath(c + a * len * f + b * depth * left, path) > 6;
      for (const auto& q : poles) ok = ok && (q - c).norm() > 0.5 * len + 1;
      if (ok)
        w.structures.push_back(
            {Cuboid{poseFromXyzYaw(c.x(), c.y(), w.terrain.height(c.x(), c.y()) + 0.5 * h - 1, yaw), {len, depth, h}},
             label::kBuilding});
    }
  }
  w.clearAlong(path, 1.0);
  return w;
}

}  // namespace slide::simulator
