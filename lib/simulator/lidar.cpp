#include "simulator/lidar.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "emulator/fast_rng.h"

namespace slide::simulator {

namespace {
std::vector<double> uniformBeams(int n, double top, double bottom) {
  std::vector<double> e(n);
  for (int i = 0; i < n; ++i) e[i] = top + (bottom - top) * i / (n - 1);
  return e;
}

double reflectivity(uint16_t semantic) {
  switch (semantic) {
    case label::kCar: return 0.6;
    case label::kPole:
    case label::kTrafficSign: return 0.8;
    case label::kTrunk: return 0.35;
    case label::kVegetation: return 0.3;
    case label::kRoad:
    case label::kParking: return 0.15;
    case label::kBuilding: return 0.45;
    default: return 0.25;
  }
}
}  // namespace

std::vector<std::string> lidarModelNames() { return {"os1-64", "hdl-64e", "vlp-16"}; }

LidarModel lidarModel(const std::string& name) {
  LidarModel m;
  m.name = name;
  if (name == "os1-64") {
    m.elevation_deg = uniformBeams(64, 16.6, -16.6);
    m.columns = 1024;
    m.max_range = 120;
    m.range_noise = 0.03;
  } else if (name == "hdl-64e") {
    m.elevation_deg = uniformBeams(32, 2.0, -8.33);
    const std::vector<double> lower = uniformBeams(32, -8.83, -24.9);
    m.elevation_deg.insert(m.elevation_deg.end(), lower.begin(), lower.end());
    m.columns = 2048;
    m.max_range = 120;
    m.range_noise = 0.02;
  } else if (name == "vlp-16") {
    m.elevation_deg = uniformBeams(16, 15, -15);
    m.columns = 1800;
    m.max_range = 100;
    m.range_noise = 0.03;
  } else {
    throw std::invalid_argument("unknown LiDAR model '" + name + "' (known: os1-64, hdl-64e, vlp-16)");
  }
  return m;
}

io::LabelledScan simulateLidarScan(const RayCaster& caster, const Pose& T_world_sensor, const LidarModel& model,
                               std::mt19937_64& rng) {
  emulator::FastRng fast(rng());  // per-point noise: a cheap generator seeded from the frame's
  auto u = [&](emulator::FastRng& f) { return f.uniform(); };
  auto noise = [&](emulator::FastRng& f) { return model.range_noise * f.normal(); };
  const Eigen::Matrix3d R = T_world_sensor.linear();
  const Eigen::Vector3d o = T_world_sensor.translation();
  std::vector<double> ce(model.beams()), se(model.beams());
  for (int b = 0; b < model.beams(); ++b) {
    const double e = model.elevation_deg[b] * M_PI / 180.0;
    ce[b] = std::cos(e);
    se[b] = std::sin(e);
  }
  io::LabelledScan scan;
  const std::size_t capacity = static_cast<std::size_t>(model.beams()) * model.columns;
  scan.xyz.reserve(capacity);
  scan.intensity.reserve(capacity);
  scan.semantic.reserve(capacity);
  scan.instance.reserve(capacity);
  const OriginView view(caster, o, model.max_range);
  RayHit hit;
  for (int c = 0; c < model.columns; ++c) {
    const double az = 2 * M_PI * c / model.columns;
    const double ca = std::cos(az), sa = std::sin(az);
    for (int b = 0; b < model.beams(); ++b) {
      const Eigen::Vector3d dir_s(ce[b] * ca, ce[b] * sa, se[b]);
      if (!view.cast(R * dir_s, model.max_range, &hit)) continue;
      if (hit.range < model.min_range) continue;
      if (model.dropout > 0 && u(fast) < model.dropout) continue;
      double range = hit.range;
      if (hit.semantic == label::kVegetation && model.foliage_depth > 0)
        range -= model.foliage_depth * std::log(std::max(u(fast), 1e-12));
      const double r = std::max(model.min_range, range + noise(fast));
      scan.xyz.push_back((r * dir_s).cast<float>());
      const double i = reflectivity(hit.semantic) * (1.0 - 0.5 * hit.range / model.max_range) + 0.05 * u(fast);
      scan.intensity.push_back(static_cast<float>(std::min(1.0, i)));
      scan.semantic.push_back(hit.semantic);
      scan.instance.push_back(hit.instance);
    }
  }
  return scan;
}

}  // namespace slide::simulator
