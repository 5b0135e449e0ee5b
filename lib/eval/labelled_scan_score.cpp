#include "eval/labelled_scan_score.h"

#include <algorithm>
#include <functional>
#include <map>
#include <stdexcept>

#include "frontend/grid_clustering.h"

namespace slide::eval {

const char* verdictName(EstimateVerdict v) {
  switch (v) {
    case EstimateVerdict::Matched: return "matched";
    case EstimateVerdict::Duplicate: return "duplicate";
    case EstimateVerdict::Small: return "small";
    case EstimateVerdict::False: return "false";
  }
  return "?";
}

namespace {
double planarDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).head<2>().norm(); }

// Nearest-first one-to-one matching of the estimates of one shape to the targets of that shape.
void matchShape(std::vector<LabelledTarget>& targets, const std::vector<int>& target_idx,
                const std::vector<Object>& est, const std::vector<int>& est_idx, double gate,
                const std::function<bool(const Object&, const LabelledTarget&)>& admissible) {
  struct Pair {
    double d;
    int e, t;
  };
  std::vector<Pair> pairs;
  for (int e : est_idx)
    for (int t : target_idx) {
      const double d = planarDistance(est[e].position(), targets[t].centroid);
      if (d <= gate && admissible(est[e], targets[t])) pairs.push_back({d, e, t});
    }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
    return a.d != b.d ? a.d < b.d : (a.e != b.e ? a.e < b.e : a.t < b.t);
  });
  std::vector<char> used_e(est.size(), 0);
  for (const Pair& p : pairs) {
    if (used_e[p.e] || targets[p.t].estimate >= 0) continue;
    used_e[p.e] = 1;
    targets[p.t].estimate = p.e;
    targets[p.t].distance = p.d;
  }
}
}  // namespace

ScanScore scoreScanAgainstLabels(const io::LabelledScan& scan, const std::vector<Object>& estimates,
                                 const ClassTable& classes, const ScanScoreParams& params) {
  if (!scan.hasLabels() || scan.semantic.size() != scan.size() || scan.instance.size() != scan.size())
    throw std::invalid_argument("scoring a scan needs one label per point");
  ScanScore s;
  std::map<int, std::pair<int, std::vector<int>>> cars;  // instance -> (class, points)
  std::map<int, std::vector<int>> columns;                // class -> points
  std::vector<int> others;
  frontend::Cloud car_points, column_points, other_points;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (!scan.xyz[i].allFinite()) continue;
    const auto cls = classes.fromSemanticKitti(scan.semantic[i]);
    const Shape shape = cls ? classes.at(*cls).shape : Shape::Ellipsoid;
    if (shape == Shape::Ellipsoid) {  // no class of ours, or one scored as an "other" thing
      if (std::find(params.other_labels.begin(), params.other_labels.end(), static_cast<int>(scan.semantic[i])) !=
          params.other_labels.end()) {
        others.push_back(static_cast<int>(i));
        other_points.push_back(scan.xyz[i]);
      }
      continue;
    }
    if (shape == Shape::Cuboid) {
      auto& c = cars[scan.instance[i]];
      c.first = *cls;
      c.second.push_back(static_cast<int>(i));
      car_points.push_back(scan.xyz[i]);
    } else if (shape == Shape::Cylinder) {
      columns[*cls].push_back(static_cast<int>(i));
      column_points.push_back(scan.xyz[i]);
    }
  }
  auto add = [&](int class_id, int instance, const std::vector<int>& idx) {
    LabelledTarget t;
    t.class_id = class_id;
    t.instance = instance;
    t.points = static_cast<int>(idx.size());
    for (int i : idx) t.centroid += scan.xyz[i].cast<double>();
    t.centroid /= static_cast<double>(idx.size());
    s.targets.push_back(t);
  };
  for (const auto& [inst, c] : cars)
    if (static_cast<int>(c.second.size()) >= params.min_car_points) add(c.first, inst, c.second);
  for (const auto& [cls, idx] : columns)
    for (const auto& cl : frontend::clusterGrid(scan.xyz, idx, {params.column_cell, false, params.min_column_points}))
      add(cls, 0, cl);
  const std::size_t first_other = s.targets.size();
  if (!others.empty())  // (an empty subset would cluster the whole scan)
    for (const auto& cl : frontend::clusterGrid(scan.xyz, others, {params.column_cell, false, params.min_column_points}))
      add(params.other_class, 0, cl);

  std::vector<int> car_t, col_t, oth_t, car_e, col_e, oth_e;
  for (std::size_t t = 0; t < s.targets.size(); ++t)
    (t >= first_other ? oth_t : classes.at(s.targets[t].class_id).shape == Shape::Cuboid ? car_t : col_t)
        .push_back(static_cast<int>(t));
  for (std::size_t e = 0; e < estimates.size(); ++e) {
    const Shape shape = estimates[e].shape();
    (shape == Shape::Cuboid ? car_e : shape == Shape::Cylinder ? col_e : oth_e).push_back(static_cast<int>(e));
  }
  const int car_class = car_t.empty() ? -1 : s.targets[car_t[0]].class_id;
  auto carSized = [&](const Object& o) {
    const ClassInfo* c = classes.find(o.class_id);
    if (!c || c->shape != Shape::Cuboid) c = car_class >= 0 ? &classes.at(car_class) : nullptr;
    if (!c) return false;
    Object probe = o;
    probe.class_id = c->id;
    return classes.sizePlausible(probe);
  };
  matchShape(s.targets, car_t, estimates, car_e, params.car_match,
             [&](const Object& o, const LabelledTarget&) { return carSized(o); });
  matchShape(s.targets, col_t, estimates, col_e, params.column_match,
             [](const Object&, const LabelledTarget&) { return true; });
  matchShape(s.targets, oth_t, estimates, oth_e, params.other_match,
             [](const Object&, const LabelledTarget&) { return true; });

  s.verdicts.assign(estimates.size(), EstimateVerdict::False);  // each judged below
  for (const auto& t : s.targets)
    if (t.estimate >= 0) s.verdicts[t.estimate] = EstimateVerdict::Matched;
  auto judge = [&](const std::vector<int>& est_idx, const std::vector<int>& target_idx, const frontend::Cloud& labelled,
                   double gate, ShapeTally& tally, bool cuboids) {
    tally.targets = static_cast<int>(target_idx.size());
    tally.estimates = static_cast<int>(est_idx.size());
    for (int t : target_idx) tally.found += s.targets[t].estimate >= 0;
    for (int e : est_idx) {
      if (s.verdicts[e] == EstimateVerdict::Matched) continue;
      const Eigen::Vector3d p = estimates[e].position();
      bool near_target = false;
      for (int t : target_idx) near_target |= planarDistance(p, s.targets[t].centroid) <= gate;
      bool near_points = false;
      for (const auto& q : labelled)
        if (planarDistance(p, q.cast<double>()) <= gate) {
          near_points = true;
          break;
        }
      if (near_target && cuboids && !carSized(estimates[e])) ++s.wrong_size_cuboids;
      EstimateVerdict& v = s.verdicts[e];
      v = near_target ? EstimateVerdict::Duplicate : near_points ? EstimateVerdict::Small : EstimateVerdict::False;
      tally.duplicates += v == EstimateVerdict::Duplicate;
      tally.small += v == EstimateVerdict::Small;
      tally.false_estimates += v == EstimateVerdict::False;
    }
  };
  judge(car_e, car_t, car_points, params.car_match, s.cars, true);
  judge(col_e, col_t, column_points, params.column_match, s.columns, false);
  judge(oth_e, oth_t, other_points, params.other_match, s.others, false);
  return s;
}

}  // namespace slide::eval
