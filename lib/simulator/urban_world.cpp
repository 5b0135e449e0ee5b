#include "simulator/urban_world.h"

#include <cmath>
#include <random>

#include "simulator/semantic_labels.h"

namespace slide::simulator {

namespace {
io::GroundTruthObject car(double x, double y, double yaw, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const bool van = u(rng) < 0.15;
  const double L = van ? 5.0 + 0.4 * u(rng) : 3.9 + 1.0 * u(rng);
  const double W = van ? 1.9 + 0.1 * u(rng) : 1.7 + 0.25 * u(rng);
  const double H = van ? 1.9 + 0.3 * u(rng) : 1.4 + 0.25 * u(rng);
  io::GroundTruthObject g;
  g.object.class_id = 10;
  g.semantic = label::kCar;
  g.object.model = Cuboid{poseFromXyzYaw(x, y, 0.5 * H, yaw), {L, W, H}};
  return g;
}

void tree(World& w, double x, double y, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const double r = 0.12 + 0.15 * u(rng), h = 6 + 4 * u(rng);
  io::GroundTruthObject g;
  g.object.class_id = 71;
  g.semantic = label::kTrunk;
  g.object.model = Cylinder{{x, y, -0.1}, Eigen::Vector3d::UnitZ(), r, 0.6 * h + 0.5};
  w.objects.push_back(g);
  w.structures.push_back({Ellipsoid{{x, y, 0.8 * h}, 1.8 + u(rng), 0.45 * h}, label::kVegetation});
}

void pole(World& w, double x, double y, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  io::GroundTruthObject g;
  g.object.class_id = 80;
  g.semantic = label::kPole;
  g.object.model = Cylinder{{x, y, -0.1}, Eigen::Vector3d::UnitZ(), 0.09 + 0.05 * u(rng), 7 + 2 * u(rng)};
  w.objects.push_back(g);
}
}  // namespace

World makeUrbanWorld(const UrbanParams& p, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> n01(0, 1);
  World w;
  w.name = "urban";
  w.terrain.semantic = label::kRoad;

  const double block = p.bays_per_block * p.bay_width;
  const double row_depth = 2 * p.bay_depth;
  const double pitch = row_depth + p.aisle;
  // Lanes: x of the left, middle and right cross lanes; y of each aisle centre.
  const double x_left = -block - 1.5 * p.aisle, x_mid = 0, x_right = block + 1.5 * p.aisle;
  std::vector<double> aisle_y;
  for (int r = 0; r <= p.double_rows; ++r) aisle_y.push_back(r * pitch);
  for (int r = 0; r < p.double_rows; ++r) {
    const double yc = aisle_y[r] + 0.5 * pitch;  // row centre line (cars back to back)
    for (int side : {-1, 1}) {
      const double x0 = side < 0 ? x_left + 0.5 * p.aisle + 1.0 : x_mid + 0.5 * p.aisle;
      for (int b = 0; b < p.bays_per_block; ++b) {
        const double x = x0 + (b + 0.5) * p.bay_width;
        for (int half : {-1, 1}) {
          if (u(rng) > p.occupancy) continue;
          const double y = yc + half * 0.5 * p.bay_depth + 0.15 * n01(rng);
          const double yaw = (u(rng) < 0.5 ? M_PI / 2 : -M_PI / 2) + 0.05 * n01(rng);
          w.objects.push_back(car(x + 0.1 * n01(rng), y, yaw, rng));
        }
      }
      // Island at each end of the row: a tree or a light pole, sometimes a bin.
      for (double xe : {x0 - 0.6, x0 + block + 0.6}) {
        if (u(rng) < 0.5) tree(w, xe, yc, rng);
        else pole(w, xe, yc, rng);
        if (u(rng) < 0.4) {
          io::GroundTruthObject bin;
          bin.object.class_id = 0;
          bin.semantic = label::kOtherObject;
          bin.object.model = Ellipsoid{{xe, yc + 1.2, 0.5}, 0.35, 1.0};
          w.objects.push_back(bin);
        }
      }
    }
  }
  // Buildings around the lot (gaps left at the corners), plus a road with moving cars.
  const double y_lo = -0.5 * p.aisle - 6, y_hi = aisle_y.back() + 0.5 * p.aisle + 14;
  const double xl = x_left - 0.5 * p.aisle - 6, xr = x_right + 0.5 * p.aisle + 6;
  auto wall = [&](double cx, double cy, double lx, double ly) {
    const double h = 6 + 10 * u(rng);
    w.structures.push_back({Cuboid{poseFromXyzYaw(cx, cy, 0.5 * h, 0), {lx, ly, h}}, label::kBuilding});
  };
  for (double x = xl + 8; x < xr - 8; x += 30) {
    wall(x + 12, y_lo - 5, 24 - 4 * u(rng), 10);
    wall(x + 12, y_hi + 5, 24 - 4 * u(rng), 10);
  }
  for (double y = y_lo + 6; y < y_hi - 6; y += 26) {
    wall(xl - 5, y + 10, 10, 20 - 4 * u(rng));
    wall(xr + 5, y + 10, 10, 20 - 4 * u(rng));
  }
  const double road_y = y_hi - 5;
  for (int i = 0; i < p.moving_cars; ++i) {
    const int dir = i % 2 ? -1 : 1;
    const double speed = 3 + 5 * u(rng);
    const double x0 = (dir > 0 ? xl : xr) - dir * 60 * u(rng);
    io::GroundTruthObject c = car(x0, road_y - dir * 1.8, dir > 0 ? 0 : M_PI, rng);
    c.velocity = {dir * speed, 0};
    w.objects.push_back(c);
  }
  for (double x = xl + 10; x < xr - 10; x += 25) pole(w, x, road_y - 4.2, rng);

  // Routes: nodes at every aisle / cross-lane crossing and halfway along each aisle block.
  const std::vector<double> xs = {x_left, 0.5 * (x_left + x_mid), x_mid, 0.5 * (x_mid + x_right), x_right};
  for (double y : aisle_y)
    for (double x : xs) w.routes.nodes.emplace_back(x, y);
  const int nx = static_cast<int>(xs.size());
  for (int r = 0; r <= p.double_rows; ++r)
    for (int i = 0; i < nx; ++i) {
      const int k = r * nx + i;
      if (i + 1 < nx) w.routes.edges.emplace_back(k, k + 1);
      if (r < p.double_rows && (i == 0 || i == 2 || i == 4)) w.routes.edges.emplace_back(k, k + nx);
    }
  w.bounds = Eigen::AlignedBox2d(Eigen::Vector2d(xl - 10, y_lo - 10), Eigen::Vector2d(xr + 10, y_hi + 10));
  w.renumber();
  return w;
}

}  // namespace slide::simulator
