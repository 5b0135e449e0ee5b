#include "worlds.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "io/kitti_poses.h"
#include "io/object_map_text.h"

namespace slide::bench_place {

namespace {
place::Landmark make(int cls, const Eigen::Vector3d& p, const Eigen::Vector3d& size, std::size_t id) {
  place::Landmark l;
  l.class_id = cls;
  l.p = p;
  l.size = size;
  l.index = id;
  return l;
}
}  // namespace

World forestWorld(double w, double h, double density, std::mt19937& rng) {
  std::poisson_distribution<int> count(density * w * h);
  std::uniform_real_distribution<double> ux(0, w), uy(0, h), radius(0.1, 0.35);
  const int n = count(rng);
  World out;
  for (int i = 0; i < n; ++i) {
    const double r = radius(rng);
    out.push_back(make(71, {ux(rng), uy(rng), 1.5}, {2 * r, 2 * r, 3.0}, out.size()));
  }
  return out;
}

World urbanWorld(double w, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> jitter(0, 0.3);
  World out;
  const double block = 60;
  for (int dir = 0; dir < 2; ++dir)
    for (double line = block / 2; line < w; line += block)
      for (int side = -1; side <= 1; side += 2)
        for (double s = 8; s < w - 8; s += 6) {
          if (std::fmod(s + block / 2, block) < 10 || std::fmod(s + block / 2, block) > block - 10) continue;  // crossings
          auto at = [&](double offset) {
            return dir == 0 ? Eigen::Vector2d(s, line + side * offset) : Eigen::Vector2d(line + side * offset, s);
          };
          if (u(rng) < 0.5) {
            const Eigen::Vector2d p = at(5.0) + Eigen::Vector2d(jitter(rng), jitter(rng));
            const Eigen::Vector3d size = dir == 0 ? Eigen::Vector3d(4.5, 1.8, 1.5) : Eigen::Vector3d(1.8, 4.5, 1.5);
            out.push_back(make(10, {p.x(), p.y(), 0.75}, size, out.size()));
          }
          if (std::fmod(s, 30) < 6 && u(rng) < 0.8) {
            const Eigen::Vector2d p = at(7.5) + Eigen::Vector2d(jitter(rng), jitter(rng));
            out.push_back(make(80, {p.x(), p.y(), 3.0}, {0.25, 0.25, 6.0}, out.size()));
          }
          if (std::fmod(s, 12) < 6 && u(rng) < 0.6) {
            const Eigen::Vector2d p = at(9.0) + Eigen::Vector2d(jitter(rng), jitter(rng));
            const double r = 0.15 + 0.2 * u(rng);
            out.push_back(make(71, {p.x(), p.y(), 1.5}, {2 * r, 2 * r, 3.0}, out.size()));
          }
          if (u(rng) < 0.12) {
            const Eigen::Vector2d p = at(8.0 + 2 * u(rng));
            out.push_back(make(0, {p.x(), p.y(), 0.5}, {0.8, 0.8, 1.0}, out.size()));
          }
        }
  return out;
}

World indoorWorld(int rooms_x, int rooms_y, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  World out;
  const double room = 8.0;
  for (int rx = 0; rx < rooms_x; ++rx)
    for (int ry = 0; ry < rooms_y; ++ry) {
      const Eigen::Vector2d corner(rx * (room + 2.0), ry * (room + 2.0));  // 2 m corridors
      const int tables = 2 + static_cast<int>(u(rng) * 2);
      for (int t = 0; t < tables; ++t) {
        const Eigen::Vector2d c = corner + Eigen::Vector2d(1.5 + u(rng) * 5, 1.5 + u(rng) * 5);
        const bool along_x = u(rng) < 0.5;
        const Eigen::Vector2d axis = along_x ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1);
        const Eigen::Vector2d across(-axis.y(), axis.x());
        out.push_back(make(2, {c.x(), c.y(), 0.4}, along_x ? Eigen::Vector3d(1.6, 0.8, 0.75) : Eigen::Vector3d(0.8, 1.6, 0.75),
                           out.size()));
        for (int k = 0; k < 4; ++k) {
          if (u(rng) < 0.3) continue;
          const Eigen::Vector2d p = c + (k % 2 ? 0.45 : -0.45) * axis + (k < 2 ? 0.75 : -0.75) * across +
                                    Eigen::Vector2d(0.15 * (u(rng) - 0.5), 0.15 * (u(rng) - 0.5));
          out.push_back(make(1, {p.x(), p.y(), 0.45}, {0.5, 0.5, 0.9}, out.size()));
        }
        if (u(rng) < 0.6) {
          const Eigen::Vector2d p = c + 0.3 * across + (u(rng) - 0.5) * axis;
          out.push_back(make(3, {p.x(), p.y(), 1.0}, {0.55, 0.2, 0.4}, out.size()));
        }
      }
    }
  return out;
}

RobotMap observe(const World& world, const std::function<bool(const place::Landmark&)>& visible, const Pose& T_w_r,
                 const place::PerturbParams& p, std::mt19937& rng) {
  World seen;
  for (const place::Landmark& l : world)
    if (visible(l)) seen.push_back(l);
  return {place::perturbedCopy(seen, T_w_r, p, rng), T_w_r};
}

Pose randomFrame(const Eigen::Vector2d& around, double spread, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  return poseFromXyzYaw(around.x() + spread * u(rng), around.y() + spread * u(rng), 0.5 * u(rng), M_PI * u(rng));
}

KittiSequence loadKitti(const std::string& data_dir, const std::string& seq) {
  KittiSequence k;
  k.poses =
      io::kittiLidarPoses(io::readKittiPoses(data_dir + "/kitti/poses/" + seq + ".txt"), io::kittiVeloToCamTr0410());
  const std::string path = data_dir + "/kitti/poles/" + seq + ".csv";
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot open");
  std::string line;
  std::getline(f, line);  // header x,y
  int lineno = 1;
  while (std::getline(f, line)) {
    ++lineno;
    if (line.empty()) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream in(line);
    double x, y;
    if (!(in >> x >> y)) throw std::runtime_error(path + ":" + std::to_string(lineno) + ": expected x,y");
    k.poles.push_back(make(80, {x, y, 0}, {0.3, 0.3, 4.0}, k.poles.size()));
  }
  // Pole centres at the height of the nearest trajectory pose (the ground is not in the data).
  for (place::Landmark& l : k.poles) {
    double best = 1e300;
    for (const Pose& T : k.poses) {
      const double d = (T.translation().head<2>() - l.p.head<2>()).squaredNorm();
      if (d < best) {
        best = d;
        l.p.z() = T.translation().z();
      }
    }
  }
  return k;
}

RobotMap kittiRobot(const KittiSequence& kitti, int first, int last, double range, const place::PerturbParams& p,
                    std::mt19937& rng) {
  last = std::min<int>(last, static_cast<int>(kitti.poses.size()) - 1);
  const Pose start = kitti.poses.at(first);
  // Level the start frame: roll and pitch are known from the IMU, so maps are gravity-aligned.
  const Pose frame = poseFromXyzYaw(start.translation().x(), start.translation().y(), start.translation().z(),
                                    yawOf(start.linear()));
  auto visible = [&](const place::Landmark& l) {
    for (int i = first; i <= last; i += 5)
      if ((kitti.poses[i].translation().head<2>() - l.p.head<2>()).norm() < range) return true;
    return false;
  };
  return observe(kitti.poles, visible, frame, p, rng);
}

std::size_t sharedLandmarks(const RobotMap& a, const RobotMap& b) {
  std::set<std::size_t> ids;
  for (const place::Landmark& l : a.lms) ids.insert(l.index);
  std::size_t n = 0;
  for (const place::Landmark& l : b.lms) n += ids.count(l.index);
  return n;
}

void writeLandmarks(const std::string& path, const std::vector<place::Landmark>& lms) {
  static const ClassTable classes = ClassTable::loadDefault();
  ObjectMap map;
  for (const place::Landmark& l : lms) map.add(io::objectFromCentre(l.class_id, l.p, l.size, classes));
  io::writeObjectMapText(path, map, classes);
}

}  // namespace slide::bench_place
