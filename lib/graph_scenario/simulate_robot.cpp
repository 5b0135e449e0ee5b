// Paths along waypoints and the noisy observation model of a simulated robot.
#include <algorithm>
#include <cmath>

#include "graph_scenario/scenario.h"

namespace slide::graph_scenario {

std::vector<Pose> pathAlongWaypoints(const std::vector<Eigen::Vector2d>& wp, int num_poses, double z) {
  std::vector<double> cumulative{0.0};
  for (std::size_t i = 1; i < wp.size(); ++i) cumulative.push_back(cumulative.back() + (wp[i] - wp[i - 1]).norm());
  const double total = cumulative.back();
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < num_poses; ++k) {
    const double s = total * k / std::max(1, num_poses - 1);
    std::size_t seg = std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin();
    seg = std::clamp<std::size_t>(seg, 1, wp.size() - 1);
    const double len = cumulative[seg] - cumulative[seg - 1];
    const double f = len > 0 ? (s - cumulative[seg - 1]) / len : 0.0;
    points.push_back(wp[seg - 1] + f * (wp[seg] - wp[seg - 1]));
  }
  std::vector<Pose> poses;
  for (int k = 0; k < num_poses; ++k) {
    const Eigen::Vector2d d = points[std::min(k + 1, num_poses - 1)] - points[std::max(k - 1, 0)];
    poses.push_back(poseFromXyzYaw(points[k].x(), points[k].y(), z, std::atan2(d.y(), d.x())));
  }
  return poses;
}

namespace {
double gauss(std::mt19937& rng, double sigma) { return std::normal_distribution<double>(0.0, sigma)(rng); }

// Moves an object seen at body position p to a range/azimuth/elevation-perturbed position.
Eigen::Vector3d perturbRangeBearing(const Eigen::Vector3d& p, const ScenarioNoise& n, std::mt19937& rng) {
  const double r = p.norm() + gauss(rng, n.range_sigma);
  const double az = std::atan2(p.y(), p.x()) + gauss(rng, n.bearing_sigma);
  const double el = std::atan2(p.z(), p.head<2>().norm()) + gauss(rng, n.bearing_sigma);
  return r * Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
}

// A trunk's position comes from a horizontal fit: range and azimuth noise in the ground
// plane, elevation noise only moves it vertically.
Eigen::Vector3d perturbGroundRangeBearing(const Eigen::Vector3d& p, const ScenarioNoise& n, std::mt19937& rng) {
  const double rho = p.head<2>().norm();
  const double r = rho + gauss(rng, n.range_sigma);
  const double az = std::atan2(p.y(), p.x()) + gauss(rng, n.bearing_sigma);
  return {r * std::cos(az), r * std::sin(az), p.z() + rho * gauss(rng, n.bearing_sigma)};
}
}  // namespace

Object observeObject(const Object& body_truth, const ScenarioNoise& n, std::mt19937& rng) {
  Object o = body_truth;
  const Eigen::Vector3d seen = o.shape() == Shape::Cylinder ? perturbGroundRangeBearing(o.position(), n, rng)
                                                            : perturbRangeBearing(o.position(), n, rng);
  const Eigen::Vector3d shift = seen - o.position();
  if (auto* c = std::get_if<Cuboid>(&o.model)) {
    c->pose.translation() += shift;
    c->pose.linear() = c->pose.linear() * rotZ(gauss(rng, n.yaw_sigma));
    for (int i = 0; i < 3; ++i) c->dims[i] = std::max(0.1, c->dims[i] + gauss(rng, n.size_sigma));
  } else if (auto* c = std::get_if<Cylinder>(&o.model)) {
    c->root += shift;
    const Eigen::Vector3d tilt(gauss(rng, n.axis_sigma), gauss(rng, n.axis_sigma), 0.0);
    c->axis = (Eigen::AngleAxisd(tilt.norm(), tilt.norm() > 0 ? tilt.normalized() : Eigen::Vector3d::UnitX()) * c->axis)
                  .normalized();
    c->radius = std::max(0.02, c->radius + gauss(rng, n.size_sigma * 0.5));
    c->length = std::max(0.5, c->length + gauss(rng, n.size_sigma * 5));
  } else {
    auto& e = std::get<Ellipsoid>(o.model);
    e.centroid += shift;
    e.radius = std::max(0.05, e.radius + gauss(rng, n.size_sigma));
    e.height = std::max(0.05, e.height + gauss(rng, n.size_sigma));
  }
  return o;
}

ScenarioRobot simulateRobot(int id, const std::vector<Pose>& truth, const std::vector<Object>& landmarks,
                            const ScenarioNoise& n, std::mt19937& rng, std::int64_t utime0) {
  ScenarioRobot robot;
  robot.id = id;
  robot.truth = truth;
  Pose odom = Pose::Identity();
  for (std::size_t k = 0; k < truth.size(); ++k) {
    KeyPoseBundle b;
    b.robot = id;
    b.seq = static_cast<int>(k);
    b.utime = utime0 + static_cast<std::int64_t>(k) * 100000;
    if (k > 0) {
      const Pose step = truth[k - 1].inverse() * truth[k];
      const double d = step.translation().norm();
      const double st = std::max(1e-3, n.odom_fraction * d);
      const double sy = std::max(1e-4, n.odom_yaw_per_m * d);
      Vector6d xi;
      xi << gauss(rng, st), gauss(rng, st), gauss(rng, st), 0.0, 0.0, gauss(rng, sy);
      Pose next = odom * step * expSE3(xi);
      // Position and heading drift; roll and pitch follow the truth (relative to the start
      // frame) with white noise, as an IMU's gravity direction keeps them.
      const Eigen::Vector3d tilt = rpyOf(truth[0].linear().transpose() * truth[k].linear());
      next = poseFromXyzRpy(next.translation(), tilt[0] + gauss(rng, n.odom_tilt_sigma),
                            tilt[1] + gauss(rng, n.odom_tilt_sigma), rpyOf(next.linear())[2]);
      b.relative_odom = odom.inverse() * next;
      const double sr = std::max(1e-4, std::sqrt(2.0) * n.odom_tilt_sigma);
      b.odom_sigma << st, st, st, sr, sr, sy;
      odom = next;
    }
    b.odom_pose = odom;
    // The nearest landmarks within range, observed with noise in the body frame.
    const Pose T_b_w = truth[k].inverse();
    std::vector<std::pair<double, int>> visible;
    for (std::size_t i = 0; i < landmarks.size(); ++i) {
      const double d = (landmarks[i].position() - truth[k].translation()).head<2>().norm();
      if (d <= n.range) visible.emplace_back(d, static_cast<int>(i));
    }
    std::sort(visible.begin(), visible.end());
    if (static_cast<int>(visible.size()) > n.max_objects) visible.resize(n.max_objects);
    std::vector<int> seen;
    for (const auto& [d, i] : visible) {
      Object o = observeObject(transformObject(T_b_w, landmarks[i]), n, rng);
      o.id = -1;
      o.num_observations = 1;
      b.objects.push_back(o);
      seen.push_back(i);
    }
    robot.bundles.push_back(std::move(b));
    robot.seen.push_back(std::move(seen));
  }
  return robot;
}

std::vector<ScenarioLoopClosure> simulateLoopClosures(const ScenarioRobot& robot, double radius, int min_gap,
                                                      int every, double metres, double radians, std::uint32_t seed) {
  std::mt19937 rng(seed + robot.id);
  std::vector<ScenarioLoopClosure> out;
  int last = -every;
  const int n = static_cast<int>(robot.truth.size());
  for (int b = min_gap; b < n; ++b) {
    if (b - last < every) continue;
    int best = -1;
    double best_d = radius;
    for (int a = 0; a + min_gap <= b; ++a) {
      const double d = (robot.truth[a].translation() - robot.truth[b].translation()).norm();
      if (d < best_d) best_d = d, best = a;
    }
    if (best < 0) continue;
    Vector6d xi;
    for (int i = 0; i < 6; ++i) xi[i] = gauss(rng, i < 3 ? metres : radians);
    out.push_back({robot.id, best, b, robot.truth[best].inverse() * robot.truth[b] * expSE3(xi)});
    last = b;
  }
  return out;
}

}  // namespace slide::graph_scenario
