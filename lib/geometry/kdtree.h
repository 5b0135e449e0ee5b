#pragma once
// A static k-d tree over points of fixed dimension (2-D/3-D positions, simplex descriptors).
// Build once, query many times; indices refer to the input order.
#include <Eigen/Core>
#include <algorithm>
#include <limits>
#include <numeric>
#include <queue>
#include <utility>
#include <vector>

namespace slide {

template <int Dim>
class KdTree {
 public:
  using Point = Eigen::Matrix<double, Dim, 1>;

  KdTree() = default;
  explicit KdTree(std::vector<Point> points) : points_(std::move(points)) {
    index_.resize(points_.size());
    std::iota(index_.begin(), index_.end(), 0);
    build(0, index_.size(), 0);
  }

  std::size_t size() const { return points_.size(); }
  const Point& point(std::size_t i) const { return points_[i]; }

  // Indices of all points within `radius` of q (unordered).
  std::vector<std::size_t> radius(const Point& q, double radius) const {
    std::vector<std::size_t> out;
    radiusRec(0, index_.size(), 0, q, radius * radius, out);
    return out;
  }

  // Up to k nearest points as (index, squared distance), nearest first.
  std::vector<std::pair<std::size_t, double>> nearest(const Point& q, std::size_t k) const {
    std::priority_queue<std::pair<double, std::size_t>> heap;  // max-heap on distance
    if (k > 0) nearestRec(0, index_.size(), 0, q, k, heap);
    std::vector<std::pair<std::size_t, double>> out(heap.size());
    for (std::size_t i = out.size(); i-- > 0; heap.pop()) out[i] = {heap.top().second, heap.top().first};
    return out;
  }

 private:
  // Subtree [lo, hi) of index_ is split at its median on axis `depth % Dim`.
  void build(std::size_t lo, std::size_t hi, int depth) {
    if (hi - lo <= 1) return;
    const std::size_t mid = lo + (hi - lo) / 2;
    const int axis = depth % Dim;
    std::nth_element(index_.begin() + lo, index_.begin() + mid, index_.begin() + hi,
                     [&](std::size_t a, std::size_t b) { return points_[a][axis] < points_[b][axis]; });
    build(lo, mid, depth + 1);
    build(mid + 1, hi, depth + 1);
  }

  void radiusRec(std::size_t lo, std::size_t hi, int depth, const Point& q, double r2,
                 std::vector<std::size_t>& out) const {
    if (lo >= hi) return;
    const std::size_t mid = lo + (hi - lo) / 2;
    const Point& p = points_[index_[mid]];
    if ((p - q).squaredNorm() <= r2) out.push_back(index_[mid]);
    const int axis = depth % Dim;
    const double d = q[axis] - p[axis];
    if (d <= 0 || d * d <= r2) radiusRec(lo, mid, depth + 1, q, r2, out);
    if (d >= 0 || d * d <= r2) radiusRec(mid + 1, hi, depth + 1, q, r2, out);
  }

  void nearestRec(std::size_t lo, std::size_t hi, int depth, const Point& q, std::size_t k,
                  std::priority_queue<std::pair<double, std::size_t>>& heap) const {
    if (lo >= hi) return;
    const std::size_t mid = lo + (hi - lo) / 2;
    const Point& p = points_[index_[mid]];
    const double d2 = (p - q).squaredNorm();
    if (heap.size() < k) {
      heap.emplace(d2, index_[mid]);
    } else if (d2 < heap.top().first) {
      heap.pop();
      heap.emplace(d2, index_[mid]);
    }
    const int axis = depth % Dim;
    const double d = q[axis] - p[axis];
    const bool left_first = d <= 0;
    if (left_first) nearestRec(lo, mid, depth + 1, q, k, heap);
    else nearestRec(mid + 1, hi, depth + 1, q, k, heap);
    if (heap.size() < k || d * d < heap.top().first) {
      if (left_first) nearestRec(mid + 1, hi, depth + 1, q, k, heap);
      else nearestRec(lo, mid, depth + 1, q, k, heap);
    }
  }

  std::vector<Point> points_;
  std::vector<std::size_t> index_;
};

}  // namespace slide
