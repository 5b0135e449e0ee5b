#pragma once
// Per-class k-d trees over the positions of a landmark set (plus one over all classes).
#include <map>

#include "geometry/kdtree.h"
#include "place/landmark.h"

namespace slide {

class LandmarkIndex {
 public:
  static constexpr int kAnyClass = ObjectMap::kAnyClass;

  explicit LandmarkIndex(const std::vector<Landmark>& lms);

  // Indices (into the landmark vector) of class `class_id` (or any) within r of p.
  std::vector<std::size_t> radius(const Eigen::Vector3d& p, double r, int class_id) const;
  // Nearest landmark of the class (or any) as (index, distance); index npos when none.
  std::pair<std::size_t, double> nearest(const Eigen::Vector3d& p, int class_id) const;
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  std::size_t count(int class_id) const;
  // Median distance from a landmark to its nearest other landmark (any class); 0 below two.
  double medianSpacing() const { return median_spacing_; }

 private:
  struct Tree {
    KdTree<3> tree;
    std::vector<std::size_t> members;
  };
  std::map<int, Tree> trees_;
  double median_spacing_ = 0;
};

}  // namespace slide
