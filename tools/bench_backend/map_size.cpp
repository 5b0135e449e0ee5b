#include "map_size.h"

#include <filesystem>
#include <stdexcept>

#include "backend/optimizer.h"
#include "team/codec.h"

namespace slide {

namespace {
// Index of the first LiDAR pose at or after `from` that is `T` (key poses are copies).
std::size_t frameOf(const std::vector<Pose>& lidar, const Pose& T, std::size_t from, int robot) {
  for (std::size_t i = from; i < lidar.size(); ++i)
    if ((lidar[i].translation() - T.translation()).norm() < 1e-9) return i;
  throw std::runtime_error("robot " + std::to_string(robot) + ": key pose not among the sequence's LiDAR poses");
}
}  // namespace

std::vector<RobotMapSize> robotMapSizes(const graph_scenario::GraphScenario& s, const backend::BackendConfig& cfg,
                                        const std::vector<Pose>& lidar, double points_per_scan) {
  std::vector<RobotMapSize> out;
  for (const graph_scenario::ScenarioRobot& r : s.robots) {
    backend::Optimizer opt(cfg, ClassTable::loadDefault(), r.id);
    for (const KeyPoseBundle& b : r.bundles) opt.addBundle(b);
    opt.fullSolve();
    team::SharedMap m;
    m.robot = m.frame_robot = r.id;
    m.version = 1;
    m.utime = r.bundles.empty() ? 0 : r.bundles.back().utime;
    m.objects = opt.landmarks(true);
    RobotMapSize size;
    size.robot = r.id;
    size.objects = static_cast<int>(m.objects.size());
    size.map_bytes = team::encodeMap(m).size();
    if (!r.truth.empty()) {
      const std::size_t first = frameOf(lidar, r.truth.front(), 0, r.id);
      size.frames = static_cast<long>(frameOf(lidar, r.truth.back(), first, r.id) - first + 1);
    }
    size.raw_bytes = size.frames * points_per_scan * 16.0;
    out.push_back(size);
  }
  return out;
}

double meanPointsPerScan(const std::string& dir) {
  namespace fs = std::filesystem;
  double points = 0;
  int scans = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.path().extension() != ".bin") continue;
    points += static_cast<double>(e.file_size()) / 16.0;
    ++scans;
  }
  if (scans == 0) throw std::runtime_error(dir + ": no KITTI .bin scan to count points per scan");
  return points / scans;
}

}  // namespace slide
