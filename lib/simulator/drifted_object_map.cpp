#include "simulator/drifted_object_map.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "place/alignment.h"

namespace slide::simulator {

namespace {
// Index of the pose of closest approach on the first pass within `range` (-1: never seen).
long firstPassClosest(const Eigen::Vector2d& p, const std::vector<Pose>& poses, double range) {
  long best = -1;
  double best_d = range;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const double d = (poses[k].translation().head<2>() - p).norm();
    if (d <= best_d) {
      best_d = d;
      best = static_cast<long>(k);
    } else if (best >= 0 && d > range) {
      break;  // the first pass is over
    }
  }
  return best;
}

Eigen::Vector3d noisySize(const Eigen::Vector3d& size, double sigma, std::normal_distribution<double>& n,
                          std::mt19937& rng) {
  if (sigma <= 0 || size.isZero()) return size;
  Eigen::Vector3d out = size;
  for (int k = 0; k < 3; ++k) out[k] = std::max(0.01, size[k] + sigma * n(rng));
  return out;
}
}  // namespace

std::vector<Pose> posesAlong(const std::vector<Eigen::Vector2d>& route, double step) {
  std::vector<Pose> out;
  step = std::max(step, 1e-3);
  double carry = 0;  // metres into the current segment where the next pose falls
  Eigen::Vector2d last = Eigen::Vector2d::Zero();
  double heading = 0;
  for (std::size_t i = 1; i < route.size(); ++i) {
    const Eigen::Vector2d d = route[i] - route[i - 1];
    const double len = d.norm();
    if (len < 1e-9) continue;
    heading = std::atan2(d.y(), d.x());
    for (double u = carry; u < len; u += step) {
      last = route[i - 1] + d * (u / len);
      out.push_back(poseFromXyzYaw(last.x(), last.y(), 0.0, heading));
    }
    carry = std::fmod(carry - len, step);
    if (carry < 0) carry += step;
  }
  if (!out.empty() && (route.back() - last).norm() > 1e-9)
    out.push_back(poseFromXyzYaw(route.back().x(), route.back().y(), 0.0, heading));
  return out;
}

std::vector<Pose> driftedOdometry(const std::vector<Pose>& truth, double yaw_rate, double scale_error, double dz_per_m) {
  std::vector<Pose> out;
  if (truth.empty()) return out;
  out.push_back(Pose::Identity());
  for (std::size_t k = 1; k < truth.size(); ++k) {
    Pose step = truth[k - 1].inverse() * truth[k];
    const double len = step.translation().norm();
    step.translation() *= 1.0 + scale_error;
    step.linear() = rotZ(yaw_rate * len) * step.linear();
    Pose next = out.back() * step;
    next.translation().z() += dz_per_m * len;
    out.push_back(next);
  }
  return out;
}

DriftedMap mapAlongRoute(const std::vector<place::Landmark>& world, const std::vector<Eigen::Vector2d>& route,
                         const MapErrorParams& p, const ClassConfusions& confusions, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  const auto sign = [&] { return u(rng) < 0.5 ? -1.0 : 1.0; };
  DriftedMap m;
  m.truth = posesAlong(route, 0.5);
  if (m.truth.empty()) return m;
  m.T_w_r = m.truth.front();
  m.yaw_rate = sign() * p.yaw_drift_deg_per_100m * M_PI / 180.0 / 100.0;
  m.odometry = driftedOdometry(m.truth, m.yaw_rate, sign() * p.scale_error, sign() * p.vertical_drift_per_100m / 100.0);
  m.s.assign(m.truth.size(), 0.0);
  for (std::size_t k = 1; k < m.truth.size(); ++k)
    m.s[k] = m.s[k - 1] + (m.truth[k].translation() - m.truth[k - 1].translation()).norm();
  const Eigen::Vector3d sigma3 = Eigen::Vector3d::Constant(p.position_sigma);
  const auto place = [&](place::Landmark l, std::size_t k, int true_class) {
    // Seen from pose k: body-frame position, placed with the odometry's pose.
    l.p = m.odometry[k] * (m.truth[k].inverse() * l.p) + sigma3.cwiseProduct(Eigen::Vector3d(n(rng), n(rng), n(rng)));
    l.size = noisySize(l.size, p.size_sigma, n, rng);
    const auto it = confusions.find(l.class_id);
    if (it != confusions.end() && !it->second.empty() && u(rng) < p.confusion)
      l.class_id = it->second[std::min(it->second.size() - 1, static_cast<std::size_t>(u(rng) * it->second.size()))];
    m.lms.push_back(l);
    m.true_class.push_back(true_class);
    m.seen_at.push_back(m.s[k]);
  };
  for (std::size_t i = 0; i < world.size(); ++i) {
    const long k = firstPassClosest(world[i].p.head<2>(), m.truth, p.range);
    if (k < 0 || u(rng) < p.missed) continue;
    place::Landmark l = world[i];
    l.index = i;
    place(l, static_cast<std::size_t>(k), world[i].class_id);
  }
  // False objects: copies of the class and size of a mapped object, seen from a random pose at a
  // random place within range (uniform over the disc) and the height of their template.
  const std::size_t mapped = m.lms.size();
  std::binomial_distribution<std::size_t> count(mapped, std::clamp(p.spurious, 0.0, 1.0));
  const std::size_t n_false = mapped ? count(rng) : 0;
  std::uniform_int_distribution<std::size_t> pick_pose(0, m.truth.size() - 1), pick_template(0, mapped ? mapped - 1 : 0);
  for (std::size_t f = 0; f < n_false; ++f) {
    const std::size_t k = pick_pose(rng);
    const std::size_t t = pick_template(rng);
    const double r = p.range * std::sqrt(u(rng)), phi = 2 * M_PI * u(rng);
    place::Landmark l;
    l.class_id = m.true_class[t];
    l.size = m.lms[t].size.isZero() ? m.lms[t].size : (m.lms[t].size * (1.0 + 0.15 * n(rng))).cwiseMax(0.05);
    const Eigen::Vector3d template_body = m.truth[k].inverse() * world[m.lms[t].index].p;
    l.p = m.truth[k] * Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi), template_body.z());
    l.index = kSpuriousObject;
    place(l, k, l.class_id);
  }
  return m;
}

std::vector<place::Landmark> mapUpTo(const DriftedMap& m, double s_max) {
  std::vector<place::Landmark> out;
  for (std::size_t i = 0; i < m.lms.size(); ++i)
    if (m.seen_at[i] <= s_max) out.push_back(m.lms[i]);
  return out;
}

SharedTruth sharedObjectTruth(const std::vector<place::Landmark>& a, const std::vector<place::Landmark>& b) {
  std::unordered_map<std::size_t, std::size_t> in_a;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].index != kSpuriousObject) in_a.emplace(a[i].index, i);
  std::vector<Eigen::Vector3d> pa, pb;
  std::unordered_map<std::size_t, bool> used;
  for (const place::Landmark& l : b) {
    const auto it = in_a.find(l.index);
    if (l.index == kSpuriousObject || it == in_a.end() || !used.emplace(l.index, true).second) continue;
    pa.push_back(a[it->second].p);
    pb.push_back(l.p);
  }
  SharedTruth t;
  t.shared = pa.size();
  if (pa.size() < 3) return t;
  const place::Alignment al = place::alignXyzYaw(pa, pb);
  t.ok = al.ok;
  t.T_a_b = al.T_a_b;
  t.rms = al.rms;
  for (const Eigen::Vector3d& q : pb) t.centroid_b += q / static_cast<double>(pb.size());
  return t;
}

}  // namespace slide::simulator
