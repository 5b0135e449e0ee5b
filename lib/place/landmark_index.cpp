#include "place/landmark_index.h"

#include <algorithm>
#include <cmath>

namespace slide::place {

LandmarkIndex::LandmarkIndex(const std::vector<Landmark>& lms) {
  std::map<int, std::vector<Eigen::Vector3d>> pts;
  std::map<int, std::vector<std::size_t>> members;
  for (std::size_t i = 0; i < lms.size(); ++i)
    for (int key : {kAnyClass, lms[i].class_id}) {
      pts[key].push_back(lms[i].p);
      members[key].push_back(i);
    }
  for (auto& [key, p] : pts) trees_[key] = Tree{KdTree<3>(std::move(p)), std::move(members[key])};
  std::vector<double> nn;
  if (const auto it = trees_.find(kAnyClass); it != trees_.end())
    for (const Landmark& l : lms) {
      const auto k = it->second.tree.nearest(l.p, 2);
      if (k.size() == 2) nn.push_back(std::sqrt(k[1].second));
    }
  if (!nn.empty()) {
    std::nth_element(nn.begin(), nn.begin() + nn.size() / 2, nn.end());
    median_spacing_ = nn[nn.size() / 2];
  }

  // The grid over the finite landmarks: 2 m cells, larger when the extent would need more than
  // kMaxCells (stray far objects), so that memory stays bounded; queries stay exact.
  double x1 = -1e300, y1 = -1e300;
  x0_ = y0_ = 1e300;
  for (std::size_t i = 0; i < lms.size(); ++i) {
    pos_.push_back(lms[i].p);
    cls_.push_back(lms[i].class_id);
    if (!lms[i].p.allFinite()) continue;
    x0_ = std::min(x0_, lms[i].p.x()), y0_ = std::min(y0_, lms[i].p.y());
    x1 = std::max(x1, lms[i].p.x()), y1 = std::max(y1, lms[i].p.y());
  }
  if (x1 < x0_) return;  // no finite landmark
  constexpr double kMaxCells = 1e6;
  cell_ = std::max(2.0, std::sqrt((x1 - x0_) * (y1 - y0_) / kMaxCells) * 1.01);
  cell_ = std::max({cell_, (x1 - x0_) / kMaxCells, (y1 - y0_) / kMaxCells});
  nx_ = static_cast<long>((x1 - x0_) / cell_) + 1;
  ny_ = static_cast<long>((y1 - y0_) / cell_) + 1;
  std::vector<std::pair<long, std::uint32_t>> cells;
  for (std::uint32_t i = 0; i < lms.size(); ++i)
    if (lms[i].p.allFinite())
      cells.emplace_back(static_cast<long>((lms[i].p.y() - y0_) / cell_) * nx_ + static_cast<long>((lms[i].p.x() - x0_) / cell_), i);
  std::sort(cells.begin(), cells.end());
  start_.assign(static_cast<std::size_t>(nx_ * ny_ + 1), 0);
  for (const auto& [c, i] : cells) ++start_[c + 1];
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  items_.reserve(cells.size());
  for (const auto& [c, i] : cells) items_.push_back(i);
}

std::vector<std::size_t> LandmarkIndex::radius(const Eigen::Vector3d& p, double r, int class_id) const {
  std::vector<std::size_t> out;
  forEachWithin(p, r, class_id, [&](std::size_t i) { out.push_back(i); });
  return out;
}

std::size_t LandmarkIndex::countWithin(const Eigen::Vector3d& p, double r, int class_id) const {
  std::size_t n = 0;
  forEachWithin(p, r, class_id, [&](std::size_t) { ++n; });
  return n;
}

bool LandmarkIndex::anyWithin(const Eigen::Vector3d& p, double r, int class_id) const {
  // Nearest is the k-d tree's quickest answer for "is there any": one query, no visitor.
  return nearest(p, class_id).second <= r;
}

std::pair<std::size_t, double> LandmarkIndex::nearest(const Eigen::Vector3d& p, int class_id) const {
  const auto it = trees_.find(class_id);
  if (it == trees_.end()) return {npos, INFINITY};
  const auto nn = it->second.tree.nearest(p, 1);
  if (nn.empty()) return {npos, INFINITY};
  return {it->second.members[nn[0].first], std::sqrt(nn[0].second)};
}

std::size_t LandmarkIndex::count(int class_id) const {
  const auto it = trees_.find(class_id);
  return it == trees_.end() ? 0 : it->second.members.size();
}

}  // namespace slide::place
