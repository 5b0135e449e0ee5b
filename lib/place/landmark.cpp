#include "place/landmark.h"

#include <algorithm>

namespace slide::place {

std::vector<Landmark> landmarksOf(const ObjectMap& map) {
  std::vector<Landmark> out;
  out.reserve(map.size());
  for (std::size_t i = 0; i < map.size(); ++i) {
    const Object& o = map[i];
    if (!o.isFinite()) continue;
    // A column (trunk, pole) is placed at its foot: where it meets the ground is seen alike by
    // every robot, while its midpoint follows how high each one saw it (range, occlusion).
    const auto* c = std::get_if<Cylinder>(&o.model);
    out.push_back({c ? c->root : o.position(), o.extent(), o.class_id, i, o.shape()});
  }
  return out;
}

std::string unusableReason(const std::vector<Landmark>& lms, std::size_t min_count, const std::string& name) {
  if (lms.empty()) return name + " is empty";
  for (const Landmark& l : lms)
    if (!l.p.allFinite() || !l.size.allFinite()) return name + " has a non-finite landmark (index " + std::to_string(l.index) + ")";
  if (lms.size() < min_count)
    return name + " has " + std::to_string(lms.size()) + " landmarks, fewer than the minimum " + std::to_string(min_count);
  double spread = 0;
  for (const Landmark& l : lms) spread = std::max(spread, (l.p - lms.front().p).head<2>().norm());
  if (spread < 1e-6) return name + " has all landmarks at one point";
  return "";
}

bool sizesAgree(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol) {
  if (a.isZero() || b.isZero()) return true;
  const Eigen::Vector3d bs(b.y(), b.x(), b.z());
  return std::min((a - b).norm(), (a - bs).norm()) <= tol;
}

double sharedClassShare(const std::vector<Landmark>& a, const std::vector<Landmark>& b) {
  auto classes = [](const std::vector<Landmark>& l) {
    std::vector<int> c;
    for (const Landmark& x : l) c.push_back(x.class_id);
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    return c;
  };
  auto share = [](const std::vector<Landmark>& l, const std::vector<int>& other) {
    if (l.empty()) return 1.0;
    const auto n = std::count_if(l.begin(), l.end(),
                                 [&](const Landmark& x) { return std::binary_search(other.begin(), other.end(), x.class_id); });
    return static_cast<double>(n) / static_cast<double>(l.size());
  };
  return std::min(share(a, classes(b)), share(b, classes(a)));
}

std::vector<Landmark> byShapeFamily(std::vector<Landmark> lms) {
  for (Landmark& l : lms) l.class_id = -1 - static_cast<int>(l.shape);
  return lms;
}

Eigen::Vector3d centroidOf(const std::vector<Landmark>& lms) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const Landmark& l : lms) c += l.p;
  return lms.empty() ? c : Eigen::Vector3d(c / static_cast<double>(lms.size()));
}

}  // namespace slide::place
