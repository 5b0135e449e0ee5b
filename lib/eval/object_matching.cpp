#include "eval/object_matching.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace slide::eval {

namespace {
double objectDistance(const Object& a, const Object& b, bool planar) {
  const Eigen::Vector3d d = a.position() - b.position();
  return planar ? d.head<2>().norm() : d.norm();
}

void finish(ClassScore& s, double sq_sum) {
  s.precision = s.num_est ? double(s.true_positives) / s.num_est : 0.0;
  s.recall = s.num_gt ? double(s.true_positives) / s.num_gt : 0.0;
  s.f1 = (s.precision + s.recall) > 0 ? 2 * s.precision * s.recall / (s.precision + s.recall) : 0.0;
  s.position_rmse = s.true_positives ? std::sqrt(sq_sum / s.true_positives) : 0.0;
}
}  // namespace

ObjectMappingScore scoreObjectMap(const std::vector<Object>& est, const std::vector<Object>& gt,
                                  const ObjectMatchOptions& opts) {
  if (!(opts.threshold > 0)) throw std::invalid_argument("object matching: threshold must be positive");
  std::vector<std::tuple<double, std::size_t, std::size_t>> candidates;
  for (std::size_t i = 0; i < est.size(); ++i)
    for (std::size_t j = 0; j < gt.size(); ++j) {
      if (opts.match_classes && est[i].class_id != gt[j].class_id) continue;
      const double d = objectDistance(est[i], gt[j], opts.planar);
      if (d <= opts.threshold) candidates.emplace_back(d, i, j);
    }
  std::sort(candidates.begin(), candidates.end());
  std::vector<bool> est_used(est.size(), false), gt_used(gt.size(), false);
  ObjectMappingScore out;
  for (const auto& [d, i, j] : candidates) {
    if (est_used[i] || gt_used[j]) continue;
    est_used[i] = gt_used[j] = true;
    out.matches.push_back({i, j, d});
  }
  std::sort(out.matches.begin(), out.matches.end(), [](const ObjectMatch& a, const ObjectMatch& b) { return a.est < b.est; });

  std::map<int, ClassScore> classes;
  std::map<int, double> sq;
  for (const Object& o : est) classes[o.class_id].num_est++;
  for (const Object& o : gt) classes[o.class_id].num_gt++;
  double sq_all = 0;
  for (const ObjectMatch& m : out.matches) {
    // Without class matching a pair counts for the estimate's class.
    const int c = est[m.est].class_id;
    classes[c].true_positives++;
    sq[c] += m.distance * m.distance;
    sq_all += m.distance * m.distance;
  }
  out.overall.num_est = est.size();
  out.overall.num_gt = gt.size();
  out.overall.true_positives = out.matches.size();
  finish(out.overall, sq_all);
  for (auto& [id, s] : classes) {
    s.class_id = id;
    finish(s, sq[id]);
    out.per_class.push_back(s);
  }
  return out;
}

std::vector<char> secondEstimates(const std::vector<Object>& est, const std::vector<Object>& gt,
                                  const ObjectMappingScore& score, const ObjectMatchOptions& opts) {
  std::vector<char> matched(est.size(), 0), taken(gt.size(), 0), second(est.size(), 0);
  for (const ObjectMatch& m : score.matches) matched.at(m.est) = 1, taken.at(m.gt) = 1;
  for (std::size_t i = 0; i < est.size(); ++i)
    for (std::size_t j = 0; j < gt.size() && !matched[i] && !second[i]; ++j)
      second[i] = taken[j] && est[i].class_id == gt[j].class_id && objectDistance(est[i], gt[j], opts.planar) <= opts.threshold;
  return second;
}

}  // namespace slide::eval
