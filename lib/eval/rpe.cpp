#include "eval/rpe.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace slide::eval {

namespace {
// atan2(sin, cos) of the rotation angle: well conditioned near zero, unlike acos of the trace
// (which turns rounding in 7-digit KITTI files into hundredths of a degree).
double rotationAngleDeg(const Eigen::Matrix3d& R) {
  const Eigen::Vector3d w(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  return std::atan2(0.5 * w.norm(), 0.5 * (R.trace() - 1.0)) * 180.0 / M_PI;
}

Pose scaled(Pose p, double s) {
  p.translation() *= s;
  return p;
}
}  // namespace

double pathLength(const std::vector<Pose>& poses) {
  double len = 0;
  for (std::size_t i = 1; i < poses.size(); ++i) len += (poses[i].translation() - poses[i - 1].translation()).norm();
  return len;
}

RpeResult relativePoseError(const std::vector<Pose>& est, const std::vector<Pose>& ref, const RpeOptions& opts) {
  if (est.size() != ref.size()) throw std::invalid_argument("RPE: trajectories differ in length");
  if (!(opts.delta > 0)) throw std::invalid_argument("RPE: delta must be positive");
  if (opts.unit == DeltaUnit::Frames && opts.delta != std::floor(opts.delta))
    throw std::invalid_argument("RPE: a delta in frames must be a whole number");
  RpeResult r;
  const std::size_t n = est.size();
  // Cumulative reference path length, for deltas in metres.
  std::vector<double> dist(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) dist[i] = dist[i - 1] + (ref[i].translation() - ref[i - 1].translation()).norm();

  std::size_t j = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (opts.unit == DeltaUnit::Frames) {
      j = i + static_cast<std::size_t>(opts.delta);
    } else {
      j = std::max(j, i + 1);
      while (j < n && dist[j] - dist[i] < opts.delta) ++j;
    }
    if (j >= n) break;
    const Pose dq = ref[i].inverse() * ref[j];
    const Pose dp = scaled(est[i], opts.scale).inverse() * scaled(est[j], opts.scale);
    const Pose E = dq.inverse() * dp;
    r.trans_errors.push_back(E.translation().norm());
    r.rot_errors_deg.push_back(rotationAngleDeg(E.linear()));
    r.first.push_back(i);
    r.second.push_back(j);
  }
  r.translation = errorStats(r.trans_errors);
  r.rotation_deg = errorStats(r.rot_errors_deg);
  return r;
}

}  // namespace slide::eval
