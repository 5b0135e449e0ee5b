#include "graph_scenario/realism.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace slide::graph_scenario {

std::string ScenarioRealism::describe() const {
  std::ostringstream s;
  s.precision(2);
  s << std::fixed << "miss " << miss_rate << ", clutter " << clutter_fraction << ", confusion " << confusion_rate
    << ", noise x" << std::setprecision(1) << noise_scale;
  if (odom_scale_error > 0) s << ", odometry scale " << 100 * odom_scale_error << " %";
  return s.str();
}

namespace {
ScenarioNoise scaled(ScenarioNoise n, double k) {
  for (double* v : {&n.range_sigma, &n.bearing_sigma, &n.odom_fraction, &n.odom_yaw_per_m, &n.odom_tilt_sigma,
                    &n.yaw_sigma, &n.axis_sigma, &n.size_sigma})
    *v *= k;
  return n;
}

// Another class of the same shape model, or the class itself when it has none.
int confusedClass(int class_id, const ClassTable& classes, std::mt19937& rng) {
  const ClassInfo* info = classes.find(class_id);
  if (!info) return class_id;
  std::vector<int> others;
  for (int id : classes.ids())
    if (id != class_id && classes.at(id).shape == info->shape) others.push_back(id);
  if (others.empty()) return class_id;
  return others[std::uniform_int_distribution<std::size_t>(0, others.size() - 1)(rng)];
}

struct FalseObject {
  Object world;  // where the false object appears to be
  int first = 0, last = 0;  // key poses that report it
};
}  // namespace

GraphScenario withRealism(const GraphScenario& s, const ScenarioRealism& r, const ClassTable& classes, std::uint32_t seed) {
  for (double v : {r.miss_rate, r.clutter_fraction, r.confusion_rate})
    if (!(v >= 0 && v < 1)) throw std::invalid_argument("withRealism: rates must lie in [0, 1)");
  if (!(r.noise_scale > 0) || r.clutter_max_views < 1)
    throw std::invalid_argument("withRealism: noise_scale must be > 0 and clutter_max_views >= 1");
  if (!(r.odom_scale_error >= 0 && r.odom_scale_error < 0.2))
    throw std::invalid_argument("withRealism: odom_scale_error must lie in [0, 0.2)");
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  GraphScenario out = s;
  const ScenarioNoise applied = scaled(s.noise, r.noise_scale);
  for (ScenarioRobot& robot : out.robots) {
    const ScenarioRobot& ideal = s.robots[&robot - out.robots.data()];
    const std::int64_t utime0 = ideal.bundles.empty() ? 0 : ideal.bundles.front().utime;
    robot = simulateRobot(ideal.id, ideal.truth, s.landmarks, applied, rng, utime0);
    // The odometry reports the nominal sigmas (those of the idealised bundles at the same steps).
    for (std::size_t k = 0; k < robot.bundles.size(); ++k) robot.bundles[k].odom_sigma = ideal.bundles[k].odom_sigma;
    if (r.odom_scale_error > 0) {
      std::mt19937 scale_rng(seed * 7919u + 104729u + static_cast<std::uint32_t>(robot.id));
      const double factor = 1.0 + r.odom_scale_error * std::normal_distribution<double>(0.0, 1.0)(scale_rng);
      for (std::size_t k = 1; k < robot.bundles.size(); ++k) {
        KeyPoseBundle& b = robot.bundles[k];
        b.relative_odom.translation() *= factor;
        b.odom_pose = robot.bundles[k - 1].odom_pose * b.relative_odom;
      }
    }

    // Missed and confused detections of true landmarks.
    std::size_t detections = 0;
    for (std::size_t k = 0; k < robot.bundles.size(); ++k) {
      auto& objects = robot.bundles[k].objects;
      auto& seen = robot.seen[k];
      std::size_t kept = 0;
      for (std::size_t i = 0; i < objects.size(); ++i) {
        if (u(rng) < r.miss_rate) continue;
        Object o = objects[i];
        if (u(rng) < r.confusion_rate) o.class_id = confusedClass(o.class_id, classes, rng);
        objects[kept] = o;
        seen[kept++] = seen[i];
      }
      objects.resize(kept);
      seen.resize(kept);
      detections += kept;
    }
    // False objects: shaped like a landmark the robot sees now, placed at a random spot within
    // its range, reported by 1..clutter_max_views consecutive key poses while in range (a bush
    // taken for a trunk, a bin for a chair).
    const double mean_views = 0.5 * (1 + r.clutter_max_views);
    const double per_keypose = robot.bundles.empty()
                                   ? 0.0
                                   : r.clutter_fraction / (1.0 - r.clutter_fraction) *
                                         static_cast<double>(detections) / robot.bundles.size() / mean_views;
    std::vector<FalseObject> falses;
    std::poisson_distribution<int> appearing(per_keypose);
    for (std::size_t k = 0; k < robot.bundles.size(); ++k) {
      if (robot.seen[k].empty()) continue;
      for (int n = appearing(rng); n > 0; --n) {
        const int src = robot.seen[k][std::uniform_int_distribution<std::size_t>(0, robot.seen[k].size() - 1)(rng)];
        const double a = 2 * M_PI * u(rng), d = s.noise.range * std::sqrt(u(rng));
        const Eigen::Vector2d at = robot.truth[k].translation().head<2>() + d * Eigen::Vector2d(std::cos(a), std::sin(a));
        Pose shift = Pose::Identity();
        shift.translation().head<2>() = at - s.landmarks[src].position().head<2>();
        const int views = std::uniform_int_distribution<int>(1, r.clutter_max_views)(rng);
        falses.push_back({transformObject(shift, s.landmarks[src]), static_cast<int>(k), static_cast<int>(k) + views - 1});
      }
    }
    for (const FalseObject& f : falses) {
      for (int k = f.first; k <= f.last && k < static_cast<int>(robot.bundles.size()); ++k) {
        const Pose& T = robot.truth[k];
        if ((f.world.position() - T.translation()).head<2>().norm() > s.noise.range) continue;
        Object o = observeObject(transformObject(T.inverse(), f.world), applied, rng);
        o.id = -1;
        o.num_observations = 1;
        robot.bundles[k].objects.push_back(o);
        robot.seen[k].push_back(-1);
      }
    }
  }
  return out;
}

}  // namespace slide::graph_scenario
