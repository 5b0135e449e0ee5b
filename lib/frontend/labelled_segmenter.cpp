#include "frontend/labelled_segmenter.h"

#include <map>

namespace slide {

std::vector<Instance> LabelledSegmenter::segment(const LabelledScan& scan, InputIssues& issues) const {
  if (scan.size() == 0) {
    issues.count("empty scan");
    return {};
  }
  if (!scan.hasLabels() || scan.semantic.size() != scan.size() || scan.instance.size() != scan.size()) {
    issues.count("scan without labels");
    return {};
  }
  const double r2 = params_.max_range * params_.max_range;
  std::map<std::pair<int, int>, std::vector<int>> groups;  // (class, instance id) -> point indices
  std::map<int, int> class_of_label;                       // cache of the class-table lookup
  long bad = 0;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const auto& p = scan.xyz[i];
    if (!p.allFinite()) {
      ++bad;
      continue;
    }
    if (double(p.x()) * p.x() + double(p.y()) * p.y() > r2) continue;
    const int label = scan.semantic[i];
    auto it = class_of_label.find(label);
    if (it == class_of_label.end()) it = class_of_label.emplace(label, classes_.fromSemanticKitti(label).value_or(-1)).first;
    if (it->second < 0) continue;
    groups[{it->second, scan.instance[i]}].push_back(static_cast<int>(i));
  }
  issues.count("non-finite point", bad);

  std::vector<Instance> out;
  auto emit = [&](int class_id, const std::vector<int>& idx) {
    if (static_cast<int>(idx.size()) < params_.min_points) return;
    Instance inst;
    inst.id = static_cast<int>(out.size()) + 1;
    inst.class_id = class_id;
    inst.points.reserve(idx.size());
    for (int i : idx) inst.points.push_back(scan.xyz[i]);
    out.push_back(std::move(inst));
  };
  for (const auto& [key, idx] : groups) {
    if (key.second != 0) {
      emit(key.first, idx);
      continue;
    }
    for (const auto& cluster : clusterGrid(scan.xyz, idx, params_.cluster)) emit(key.first, cluster);
  }
  return out;
}

}  // namespace slide
