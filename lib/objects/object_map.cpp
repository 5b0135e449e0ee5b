#include "objects/object_map.h"

namespace slide {

std::size_t ObjectMap::add(const Object& o) {
  objects_.push_back(o);
  stale_ = true;
  return objects_.size() - 1;
}

Object& ObjectMap::operator[](std::size_t i) {
  stale_ = true;
  return objects_[i];
}

const ObjectMap::Index* ObjectMap::indexFor(int class_id) const {
  if (stale_) {
    index_.clear();
    std::map<int, std::vector<Eigen::Vector3d>> points;
    std::map<int, std::vector<std::size_t>> members;
    for (std::size_t i = 0; i < objects_.size(); ++i) {
      for (int key : {kAnyClass, objects_[i].class_id}) {
        points[key].push_back(objects_[i].position());
        members[key].push_back(i);
      }
    }
    for (auto& [key, pts] : points) index_[key] = Index{KdTree<3>(std::move(pts)), std::move(members[key])};
    stale_ = false;
  }
  const auto it = index_.find(class_id);
  return it == index_.end() ? nullptr : &it->second;
}

std::vector<std::size_t> ObjectMap::radius(const Eigen::Vector3d& p, double r, int class_id) const {
  std::vector<std::size_t> out;
  if (const Index* idx = indexFor(class_id))
    for (std::size_t i : idx->tree.radius(p, r)) out.push_back(idx->members[i]);
  return out;
}

std::vector<std::pair<std::size_t, double>> ObjectMap::nearest(const Eigen::Vector3d& p, std::size_t k,
                                                               int class_id) const {
  std::vector<std::pair<std::size_t, double>> out;
  if (const Index* idx = indexFor(class_id))
    for (const auto& [i, d2] : idx->tree.nearest(p, k)) out.emplace_back(idx->members[i], std::sqrt(d2));
  return out;
}

ObjectMap ObjectMap::transformed(const Pose& T) const {
  ObjectMap out;
  for (const Object& o : objects_) out.add(transformObject(T, o));
  return out;
}

}  // namespace slide
