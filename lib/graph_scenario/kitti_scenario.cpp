// KITTI scenarios: real LiDAR paths cut into several robots, observing the real pole map.
#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io/io_error.h"
#include "io/kitti_poses.h"
#include "graph_scenario/scenario.h"

namespace slide::graph_scenario {

namespace {
std::vector<Eigen::Vector2d> readPoles(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open pole map " + path);
  std::vector<Eigen::Vector2d> out;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == 'x' || line[0] == '#') continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream ss(line);
    double x, y;
    if (!(ss >> x >> y)) throw std::runtime_error(path + ":" + std::to_string(line_no) + ": expected 'x,y'");
    out.emplace_back(x, y);
  }
  return out;
}
}  // namespace

GraphScenario makeKittiScenario(const std::string& name, const std::string& poses_file, const std::string& poles_file,
                           int num_robots, double spacing, std::uint32_t seed) {
  if (num_robots < 1) throw std::invalid_argument("makeKittiScenario: num_robots must be at least 1");
  std::mt19937 rng(seed);
  const std::vector<Pose> lidar = io::kittiLidarPoses(io::readKittiPoses(poses_file), io::kittiVeloToCamTr0410());
  std::vector<Pose> keyposes{lidar.front()};
  for (const Pose& T : lidar)
    if ((T.translation() - keyposes.back().translation()).norm() >= spacing) keyposes.push_back(T);

  GraphScenario s;
  s.name = name;
  s.noise.range = 20.0;
  for (const Eigen::Vector2d& p : readPoles(poles_file)) {
    // Root on the ground below the nearest key pose (the LiDAR is 1.73 m up).
    double best = 1e18, z = 0;
    for (const Pose& T : keyposes) {
      const double d = (T.translation().head<2>() - p).norm();
      if (d < best) {
        best = d;
        z = T.translation().z() - 1.73;
      }
    }
    Object o;
    o.id = static_cast<std::int64_t>(s.landmarks.size());
    o.class_id = 80;
    o.model = Cylinder{Eigen::Vector3d(p.x(), p.y(), z), Eigen::Vector3d::UnitZ(), 0.15, 4.0};
    s.landmarks.push_back(o);
  }
  const std::size_t per = keyposes.size() / num_robots;
  for (int r = 0; r < num_robots; ++r) {
    const auto first = keyposes.begin() + r * per;
    const auto last = r + 1 == num_robots ? keyposes.end() : first + per;
    s.robots.push_back(simulateRobot(r, std::vector<Pose>(first, last), s.landmarks, s.noise, rng,
                                     static_cast<std::int64_t>(r) * 1000000000LL));
  }
  return s;
}

}  // namespace slide::graph_scenario
