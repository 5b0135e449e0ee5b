#include "team_scenario.h"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

namespace slide::team::bench {
namespace {

constexpr double kRange = 15.0, kStep = 1.4;
constexpr std::size_t kMaxSeen = 20;

std::vector<WorldObject> forest(std::mt19937_64& rng, double size) {
  // Density chosen so that ~12 trunks are within 15 m (0.017 per m^2).
  std::uniform_real_distribution<double> u(0, size), r(0.1, 0.35), len(3, 8);
  const int n = static_cast<int>(0.017 * size * size);
  std::vector<WorldObject> w;
  for (int i = 0; i < n; ++i) {
    Object o;
    o.id = i;
    o.class_id = 71;
    o.model = Cylinder{{u(rng), u(rng), 0}, Eigen::Vector3d::UnitZ(), r(rng), len(rng)};
    w.push_back({o});
  }
  return w;
}

std::vector<WorldObject> urban(std::mt19937_64& rng, double size, double block) {
  std::uniform_real_distribution<double> gap(2.5, 7), side(0, 1), jitter(-0.3, 0.3);
  std::vector<WorldObject> w;
  auto add = [&](Object o) {
    o.id = static_cast<std::int64_t>(w.size());
    w.push_back({o});
  };
  for (double street = 0; street <= size; street += block) {
    for (int dir = 0; dir < 2; ++dir) {  // streets along x and along y
      for (double s = 0; s < size; s += gap(rng)) {
        const double off = (side(rng) < 0.5 ? -1 : 1) * (4.5 + jitter(rng));
        const Eigen::Vector2d p = dir == 0 ? Eigen::Vector2d(s, street + off) : Eigen::Vector2d(street + off, s);
        const double k = side(rng);
        Object o;
        if (k < 0.6) {  // parked car, aligned with the street
          Cuboid c;
          c.pose = poseFromXyzYaw(p.x(), p.y(), 0.75, (dir == 0 ? 0 : M_PI / 2) + 0.05 * jitter(rng));
          c.dims = {4.5 + jitter(rng), 1.8, 1.5};
          o.model = c;
          o.class_id = 10;
        } else if (k < 0.8) {  // pole
          o.model = Cylinder{{p.x(), p.y(), 0}, Eigen::Vector3d::UnitZ(), 0.12, 6};
          o.class_id = 80;
        } else {  // bin, bench, bush
          o.model = Ellipsoid{{p.x(), p.y(), 0.5}, 0.5 + std::abs(jitter(rng)), 1.0};
          o.class_id = 0;
        }
        add(o);
      }
    }
  }
  return w;
}

// Waypoint paths: forest robots wander smoothly inside the area; urban robots follow streets.
std::vector<Pose> forestPath(std::mt19937_64& rng, double size, int n, Eigen::Vector2d start) {
  std::normal_distribution<double> turn(0, 0.25);
  std::vector<Pose> path;
  Eigen::Vector2d p = start;
  double yaw = std::uniform_real_distribution<double>(-M_PI, M_PI)(rng);
  for (int i = 0; i < n; ++i) {
    path.push_back(poseFromXyzYaw(p.x(), p.y(), 0, yaw));
    yaw = wrapAngle(yaw + turn(rng));
    Eigen::Vector2d next = p + kStep * Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
    if (next.x() < 20 || next.y() < 20 || next.x() > size - 20 || next.y() > size - 20) {
      yaw = std::atan2(size / 2 - p.y(), size / 2 - p.x()) + turn(rng);  // head back inside
      next = p + kStep * Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
    }
    p = next;
  }
  return path;
}

std::vector<Pose> urbanPath(std::mt19937_64& rng, double size, double block, int n, Eigen::Vector2i start) {
  std::vector<Pose> path;
  Eigen::Vector2d p = start.cast<double>() * block;
  Eigen::Vector2i dir(1, 0);
  const int cells = static_cast<int>(size / block);
  Eigen::Vector2i node = start;
  double along = 0;
  for (int i = 0; i < n; ++i) {
    path.push_back(poseFromXyzYaw(p.x(), p.y(), 0, std::atan2(dir.y(), dir.x())));
    p += kStep * dir.cast<double>();
    along += kStep;
    if (along >= block) {  // at a crossing: go on, or turn
      along -= block;
      node += dir;
      std::vector<Eigen::Vector2i> options;
      for (Eigen::Vector2i d : {dir, Eigen::Vector2i(-dir.y(), dir.x()), Eigen::Vector2i(dir.y(), -dir.x())}) {
        const Eigen::Vector2i nn = node + d;
        if (nn.x() >= 0 && nn.y() >= 0 && nn.x() <= cells && nn.y() <= cells) options.push_back(d);
      }
      if (options.empty()) options.push_back(-dir);
      dir = options[rng() % options.size()];
      p = node.cast<double>() * block + along * dir.cast<double>();
    }
  }
  return path;
}

}  // namespace

TeamScenario makeScenario(const std::string& kind, int robots, int keyposes, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  TeamScenario sc;
  sc.name = kind;
  const double size = kind == "forest" ? 240 : 250, block = 50;
  if (kind == "forest") sc.world = forest(rng, size);
  else if (kind == "urban") sc.world = urban(rng, size, block);
  else throw std::invalid_argument("unknown team scenario '" + kind + "' (forest or urban)");

  std::normal_distribution<double> noise(0, 1);
  std::uniform_real_distribution<double> conf(0.5, 1.0);
  std::set<std::int64_t> seen_any;
  std::size_t total_seen = 0, total_keyposes = 0;
  for (int r = 0; r < robots; ++r) {
    RobotStream rs;
    rs.robot = r + 1;
    std::vector<Pose> truth;
    if (kind == "forest") {
      const Eigen::Vector2d start(size / 2 + 40 * std::cos(2 * M_PI * r / robots), size / 2 + 40 * std::sin(2 * M_PI * r / robots));
      truth = forestPath(rng, size, keyposes, start);
    } else {
      truth = urbanPath(rng, size, block, keyposes, Eigen::Vector2i(r % 3 + 1, (r / 3) % 3 + 1));
    }
    rs.start = truth.front();
    Pose odom = Pose::Identity();  // odometry frame = first true pose
    std::map<std::int64_t, std::int64_t> track_of;  // landmark -> tracker id
    std::map<std::int64_t, int> observations;
    std::map<std::int64_t, Object> own_map;          // tracker id -> object in the odometry frame
    for (int k = 0; k < keyposes; ++k) {
      KeyPoseBundle b;
      b.robot = rs.robot;
      b.seq = k;
      b.utime = 1700000000000000LL + static_cast<std::int64_t>(k) * 1000000LL;
      if (k > 0) {
        const Pose rel_true = truth[k - 1].inverse() * truth[k];
        Vector6d xi = Vector6d::Zero();
        for (int i = 0; i < 3; ++i) xi[i] = 0.02 * noise(rng);
        xi[5] = 0.005 * noise(rng);
        b.relative_odom = rel_true * expSE3(xi);
        odom = odom * b.relative_odom;
        rs.metres += rel_true.translation().norm();
      }
      b.odom_pose = odom;
      b.odom_sigma << 0.02f, 0.02f, 0.01f, 0.002f, 0.002f, 0.005f;  // float values, as on the bus
      // Objects within range, nearest first, at most kMaxSeen, in the body frame with noise.
      std::vector<std::pair<double, std::size_t>> near;
      for (std::size_t i = 0; i < sc.world.size(); ++i) {
        const double d = (sc.world[i].model.position().head<2>() - truth[k].translation().head<2>()).norm();
        if (d <= kRange) near.emplace_back(d, i);
      }
      std::sort(near.begin(), near.end());
      if (near.size() > kMaxSeen) near.resize(kMaxSeen);
      const Pose body_from_world = truth[k].inverse();
      for (const auto& [d, i] : near) {
        const Object& w = sc.world[i].model;
        Object o = transformObject(body_from_world, w);
        const Eigen::Vector3d dp(0.05 * noise(rng), 0.05 * noise(rng), 0.05 * noise(rng));
        if (auto* c = std::get_if<Cylinder>(&o.model)) {
          c->root += dp;
          c->axis = (c->axis + Eigen::Vector3d(0.02 * noise(rng), 0.02 * noise(rng), 0)).normalized();
          c->radius = std::max(0.05, c->radius + 0.02 * noise(rng));
          c->length = std::max(0.5, c->length + 0.3 * noise(rng));
        } else if (auto* cb = std::get_if<Cuboid>(&o.model)) {
          cb->pose = poseFromXyzYaw(cb->pose.translation().x() + dp.x(), cb->pose.translation().y() + dp.y(),
                                    cb->pose.translation().z() + dp.z(), yawOf(cb->pose.linear()) + 0.03 * noise(rng));
          cb->dims += 0.05 * Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
        } else {
          auto& e = std::get<Ellipsoid>(o.model);
          e.centroid += dp;
          e.radius = std::max(0.1, e.radius + 0.05 * noise(rng));
        }
        auto t = track_of.emplace(w.id, static_cast<std::int64_t>(track_of.size())).first->second;
        o.id = t;
        o.num_observations = ++observations[w.id];
        o.confidence = conf(rng);
        b.objects.push_back(o);
        own_map[t] = transformObject(odom, o);
        own_map[t].num_observations = o.num_observations;
        seen_any.insert(w.id);
      }
      total_seen += b.objects.size();
      ++total_keyposes;
      SharedMap m;
      m.robot = rs.robot;
      m.frame_robot = rs.robot;
      m.utime = b.utime;
      for (const auto& [id, o] : own_map) m.objects.push_back(o);
      rs.maps.push_back(std::move(m));
      rs.bundles.push_back(std::move(b));
    }
    sc.robots.push_back(std::move(rs));
  }
  sc.landmarks_seen = seen_any.size();
  sc.mean_objects_per_keypose = static_cast<double>(total_seen) / static_cast<double>(std::max<std::size_t>(1, total_keyposes));
  return sc;
}

}  // namespace slide::team::bench
