#include "frontend/labelled_segmenter.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <opencv2/imgproc.hpp>

namespace slide::frontend {

LabelledSegmenter::LabelledSegmenter(ClassTable classes, LabelledSegmenterParams params)
    : classes_(std::move(classes)), params_(std::move(params)) {
  for (const auto& [name, cell] : params_.cluster_cell_by_class) {
    const ClassInfo* c = classes_.findByName(name);
    if (!c) throw std::invalid_argument("cluster_cell_by_class: no class named '" + name + "' in the class table");
    cell_of_class_[c->id] = cell;
  }
}

std::vector<Instance> LabelledSegmenter::segment(const io::LabelledScan& scan, InputIssues& issues) const {
  if (scan.size() == 0) {
    issues.count("empty scan");
    return {};
  }
  if (!scan.hasLabels() || scan.semantic.size() != scan.size()) {
    issues.count("scan without labels");
    return {};
  }
  const double r2 = params_.max_range * params_.max_range;
  // Clustering group of each class: the class itself, or -1 for every cylinder class.
  std::map<int, std::vector<int>> groups;   // group -> point indices
  std::vector<int> class_of(scan.size(), -1);
  std::map<int, int> class_of_label;        // cache of the class-table lookup
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
    class_of[i] = it->second;
    const bool cylinder = classes_.at(it->second).shape == Shape::Cylinder;
    groups[params_.merge_cylinders && cylinder ? -1 : it->second].push_back(static_cast<int>(i));
  }
  issues.count("non-finite point", bad);

  std::vector<Instance> out;
  for (const auto& [group, idx] : groups) {
    GridClusterParams cp = params_.cluster;
    // Columns are vertical: cluster their points on x, y so a trunk split by occlusion or
    // bled labels in the middle stays one object.
    cp.planar = group == -1 || (group >= 0 && classes_.at(group).shape == Shape::Cylinder);
    if (const auto it = cell_of_class_.find(group); it != cell_of_class_.end()) cp.cell = it->second;
    std::vector<std::vector<int>> clusters = clusterGrid(scan.xyz, idx, cp);
    if (group >= 0 && classes_.at(group).shape == Shape::Cuboid && params_.min_split_cell < cp.cell) {
      // Boxes parked a few decimetres apart join at cp.cell: a cluster whose footprint is
      // larger than the class is clustered again on cells half as large (down to min_split_cell).
      const ClassInfo& info = classes_.at(group);
      std::vector<std::vector<int>> kept;
      std::vector<std::pair<std::vector<int>, double>> todo;
      for (auto& c : clusters) todo.emplace_back(std::move(c), cp.cell);
      for (std::size_t k = 0; k < todo.size(); ++k) {
        auto [c, cell] = std::move(todo[k]);
        if (auto parts = splitAtNotch(scan.xyz, c, params_.notch)) {
          for (auto* part : {&parts->first, &parts->second})
            if (static_cast<int>(part->size()) >= cp.min_points) todo.emplace_back(std::move(*part), cell);
          continue;
        }
        std::vector<cv::Point2f> xy;
        xy.reserve(c.size());
        for (int i : c) xy.emplace_back(scan.xyz[i].x(), scan.xyz[i].y());
        const cv::Size2f r = cv::minAreaRect(xy).size;
        const bool oversized = std::max(r.width, r.height) > info.size_max.x() || std::min(r.width, r.height) > info.size_max.y();
        // Car-sized, but falling apart on gap_cluster cells (an end face joined to a stripe of the
        // next car's side seen through the gap): each part is a cluster of its own.
        if (!oversized && params_.gap_cluster.cell > 0 && cell > params_.gap_cluster.cell + 1e-9) {
          auto parts = clusterGrid(scan.xyz, c, params_.gap_cluster);
          if (parts.size() >= 2) {
            for (auto& part : parts) todo.emplace_back(std::move(part), params_.gap_cluster.cell);
            continue;
          }
        }
        if (!oversized || 0.5 * cell < params_.min_split_cell - 1e-9) {
          kept.push_back(std::move(c));
          continue;
        }
        for (auto& part : clusterGrid(scan.xyz, c, {0.5 * cell, false, cp.min_points})) todo.emplace_back(std::move(part), 0.5 * cell);
      }
      clusters = std::move(kept);
    }
    for (const auto& cluster : clusters) {
      if (static_cast<int>(cluster.size()) < params_.min_points) continue;
      std::map<int, int> votes;
      for (int i : cluster) ++votes[class_of[i]];
      int best = group, most = -1;
      for (const auto& [c, n] : votes)
        if (n > most) best = c, most = n;
      // A flat patch (ground or a roof labelled as an object) is no object: the cluster must
      // stand at least min_height_fraction of its class's smallest height.
      float z_lo = 1e9f, z_hi = -1e9f;
      for (int i : cluster) z_lo = std::min(z_lo, scan.xyz[i].z()), z_hi = std::max(z_hi, scan.xyz[i].z());
      if (z_hi - z_lo < params_.min_height_fraction * classes_.at(best).size_min.z()) continue;
      Instance inst;
      inst.id = static_cast<int>(out.size()) + 1;
      inst.class_id = best;
      inst.points.reserve(cluster.size());
      for (int i : cluster) inst.points.push_back(scan.xyz[i]);
      out.push_back(std::move(inst));
    }
  }
  return out;
}

}  // namespace slide::frontend
