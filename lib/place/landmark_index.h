#pragma once
// Spatial queries over a landmark set for verification: a bucket grid over x, y (one CSR over
// all classes) answers "which landmarks of this class lie within r (3-D) of p" without
// allocating, and per-class k-d trees answer nearest-landmark queries. The index copies what it
// needs (positions, classes): the landmark vector need not outlive it.
#include <map>

#include "geometry/kdtree.h"
#include "place/landmark.h"

namespace slide::place {

class LandmarkIndex {
 public:
  static constexpr int kAnyClass = ObjectMap::kAnyClass;

  explicit LandmarkIndex(const std::vector<Landmark>& lms);

  // Calls f(index) for each landmark of class `class_id` (or any) within r (3-D) of p, in no
  // particular order.
  template <class F>
  void forEachWithin(const Eigen::Vector3d& p, double r, int class_id, F&& f) const;
  // Indices (into the landmark vector) of class `class_id` (or any) within r of p.
  std::vector<std::size_t> radius(const Eigen::Vector3d& p, double r, int class_id) const;
  std::size_t countWithin(const Eigen::Vector3d& p, double r, int class_id) const;
  bool anyWithin(const Eigen::Vector3d& p, double r, int class_id) const;
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
  // Grid: cells of cell_ metres from (x0_, y0_), nx_ x ny_ of them; start_ is the CSR over cells
  // of items_ (landmark indices); positions and classes copied.
  double cell_ = 1, x0_ = 0, y0_ = 0;
  long nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> start_, items_;
  std::vector<Eigen::Vector3d> pos_;
  std::vector<int> cls_;
};

template <class F>
void LandmarkIndex::forEachWithin(const Eigen::Vector3d& p, double r, int class_id, F&& f) const {
  if (items_.empty() || !(r >= 0) || !p.allFinite()) return;
  const long cx0 = std::max(0L, static_cast<long>(std::floor((p.x() - r - x0_) / cell_)));
  const long cx1 = std::min(nx_ - 1, static_cast<long>(std::floor((p.x() + r - x0_) / cell_)));
  const long cy0 = std::max(0L, static_cast<long>(std::floor((p.y() - r - y0_) / cell_)));
  const long cy1 = std::min(ny_ - 1, static_cast<long>(std::floor((p.y() + r - y0_) / cell_)));
  const double r2 = r * r;
  for (long cy = cy0; cy <= cy1; ++cy)
    for (long cx = cx0; cx <= cx1; ++cx) {
      const long c = cy * nx_ + cx;
      for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
        const std::uint32_t i = items_[k];
        if ((class_id == kAnyClass || cls_[i] == class_id) && (pos_[i] - p).squaredNorm() <= r2) f(static_cast<std::size_t>(i));
      }
    }
}

}  // namespace slide::place
