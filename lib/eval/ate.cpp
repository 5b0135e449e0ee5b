#include "eval/ate.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "bench/stats.h"

namespace slide::eval {

AteResult absoluteTrajectoryError(const std::vector<Pose>& est, const std::vector<Pose>& ref, TrajectoryAlignment mode) {
  if (est.size() != ref.size()) throw std::invalid_argument("ATE: trajectories differ in length");
  std::vector<Eigen::Vector3d> pe, pr;
  for (std::size_t i = 0; i < est.size(); ++i) {
    pe.push_back(est[i].translation());
    pr.push_back(ref[i].translation());
  }
  AteResult r;
  r.alignment = align(pe, pr, mode);
  double sq = 0;
  for (std::size_t i = 0; i < pe.size(); ++i) {
    const Eigen::Vector3d p = r.alignment.scale * (r.alignment.T.linear() * pe[i]) + r.alignment.T.translation();
    const double e = (p - pr[i]).norm();
    r.errors.push_back(e);
    sq += e * e;
  }
  if (!r.errors.empty()) {
    r.rmse = std::sqrt(sq / r.errors.size());
    r.mean = bench::mean(r.errors);
    r.median = bench::median(r.errors);
    r.max = *std::max_element(r.errors.begin(), r.errors.end());
  }
  return r;
}

}  // namespace slide::eval
