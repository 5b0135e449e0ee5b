#include "eval/time_association.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace slide::eval {

std::vector<std::pair<std::size_t, std::size_t>> associateByTime(const std::vector<double>& est_t,
                                                                 const std::vector<double>& ref_t, double max_dt,
                                                                 double offset) {
  std::vector<std::size_t> order(ref_t.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ref_t[a] < ref_t[b]; });

  std::vector<std::tuple<double, std::size_t, std::size_t>> candidates;  // (|dt|, est, ref)
  for (std::size_t i = 0; i < est_t.size() && !order.empty(); ++i) {
    const double t = est_t[i] + offset;
    auto it = std::lower_bound(order.begin(), order.end(), t, [&](std::size_t j, double v) { return ref_t[j] < v; });
    std::size_t best = order.size();
    double best_dt = max_dt;
    for (auto c : {it, it == order.begin() ? it : it - 1}) {
      if (c == order.end()) continue;
      const double dt = std::abs(ref_t[*c] - t);
      if (dt <= best_dt) {
        best_dt = dt;
        best = *c;
      }
    }
    if (best != order.size()) candidates.emplace_back(best_dt, i, best);
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<bool> ref_used(ref_t.size(), false);
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (const auto& [dt, i, j] : candidates) {
    if (ref_used[j]) continue;
    ref_used[j] = true;
    pairs.emplace_back(i, j);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

AssociatedPoses associatePoses(const std::vector<StampedPose>& est, const std::vector<StampedPose>& ref,
                               double max_dt, double offset, std::size_t min_pairs) {
  std::vector<double> te, tr;
  for (const auto& p : est) te.push_back(p.t);
  for (const auto& p : ref) tr.push_back(p.t);
  AssociatedPoses out;
  for (const auto& [i, j] : associateByTime(te, tr, max_dt, offset)) {
    out.t.push_back(ref[j].t);
    out.est.push_back(est[i].pose);
    out.ref.push_back(ref[j].pose);
  }
  if (out.t.size() < min_pairs) {
    std::ostringstream m;
    m << "only " << out.t.size() << " poses matched in time (need " << min_pairs << ", max difference " << max_dt
      << " s); estimate spans ";
    if (est.empty()) m << "nothing"; else m << "[" << est.front().t << ", " << est.back().t << "]";
    m << ", reference spans ";
    if (ref.empty()) m << "nothing"; else m << "[" << ref.front().t << ", " << ref.back().t << "]";
    throw std::invalid_argument(m.str());
  }
  return out;
}

}  // namespace slide::eval
