#include "place/landmark_index.h"

#include <algorithm>
#include <cmath>

namespace slide {

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
}

std::vector<std::size_t> LandmarkIndex::radius(const Eigen::Vector3d& p, double r, int class_id) const {
  std::vector<std::size_t> out;
  const auto it = trees_.find(class_id);
  if (it == trees_.end()) return out;
  for (std::size_t i : it->second.tree.radius(p, r)) out.push_back(it->second.members[i]);
  return out;
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

}  // namespace slide
