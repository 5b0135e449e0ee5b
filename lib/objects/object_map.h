#pragma once
// A set of objects with a spatial index on their positions, overall and per class.
// The index is rebuilt lazily on the first query after a change.
// Vocabulary: in namespace slide itself, not slide::objects, as every area uses it (README).
#include <map>
#include <memory>
#include <vector>

#include "geometry/kdtree.h"
#include "objects/object.h"

namespace slide {

class ObjectMap {
 public:
  static constexpr int kAnyClass = -1;

  ObjectMap() = default;
  explicit ObjectMap(std::vector<Object> objects) : objects_(std::move(objects)) {}

  std::size_t add(const Object& o);  // returns the object's index
  Object& operator[](std::size_t i);  // marks the index stale
  const Object& operator[](std::size_t i) const { return objects_[i]; }
  const std::vector<Object>& objects() const { return objects_; }
  std::size_t size() const { return objects_.size(); }
  bool empty() const { return objects_.empty(); }

  // Indices of objects (of class `class_id`, or any) whose position is within `radius` of p.
  std::vector<std::size_t> radius(const Eigen::Vector3d& p, double radius, int class_id = kAnyClass) const;
  // Up to k nearest (index, distance), nearest first.
  std::vector<std::pair<std::size_t, double>> nearest(const Eigen::Vector3d& p, std::size_t k,
                                                      int class_id = kAnyClass) const;

  // The map as seen from another frame (T maps this map's frame into the new one).
  ObjectMap transformed(const Pose& T) const;

 private:
  struct Index {
    KdTree<3> tree;
    std::vector<std::size_t> members;  // tree point i is objects_[members[i]]
  };
  const Index* indexFor(int class_id) const;

  std::vector<Object> objects_;
  mutable std::map<int, Index> index_;  // keyed by class id, kAnyClass for all
  mutable bool stale_ = true;
};

}  // namespace slide
