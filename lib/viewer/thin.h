#pragma once
// Thinning for the viewer: indices strided evenly, and a frame's instances cut to a point budget
// (what a browser gets of a scan, and the segmenter's preview of it that the run logs keep).
#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace slide::viewer {

// Indices 0..n-1 thinned to at most `keep`, evenly, always with the last one.
std::vector<std::size_t> evenIndices(std::size_t n, std::size_t keep);

// At most `max_points` points of a frame's instances, each instance keeping a share in
// proportion to its size (at least one point), evenly strided; non-finite points are left out,
// and so is an instance left with none (when there are more instances than points, the first
// ones). `Instance` is any struct with `std::vector<Eigen::Vector3f> points`; its other fields
// are kept.
template <class Instance>
std::vector<Instance> thinInstances(std::vector<Instance> instances, std::size_t max_points) {
  std::size_t total = 0;
  for (const Instance& inst : instances) total += inst.points.size();
  std::vector<Instance> out;
  std::size_t used = 0;
  for (Instance& inst : instances) {
    if (used >= max_points) break;
    std::size_t share = total <= max_points ? inst.points.size()
                                            : std::max<std::size_t>(1, inst.points.size() * max_points / total);
    share = std::min(share, max_points - used);
    const std::vector<Eigen::Vector3f> all = std::move(inst.points);
    inst.points.clear();
    for (std::size_t i : evenIndices(all.size(), share))
      if (all[i].allFinite()) inst.points.push_back(all[i]);
    used += inst.points.size();
    if (!inst.points.empty()) out.push_back(std::move(inst));
  }
  return out;
}

}  // namespace slide::viewer
