#pragma once
// A static k-d tree over points of fixed dimension (2-D/3-D positions, simplex descriptors):
// nanoflann's index behind the project's small interface. Build once, query many times;
// indices refer to the input order. Copies share the (immutable) index.
// nanoflann won over the project's own tree on real stem layouts and a laser scan: 2.6-4.2x
// faster radius queries, 1.8-6.3x faster 8-NN (slide-bench-kdtree, see BENCHMARKS.md).
// Vocabulary: in namespace slide itself, not slide::geometry, as every area uses it (README).
#include <Eigen/Core>
#include <nanoflann.hpp>

#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace slide {

template <int Dim>
class KdTree {
 public:
  using Point = Eigen::Matrix<double, Dim, 1>;

  KdTree() = default;
  explicit KdTree(std::vector<Point> points) : state_(std::make_shared<State>(std::move(points))) {}

  std::size_t size() const { return state_ ? state_->cloud.pts.size() : 0; }
  const Point& point(std::size_t i) const { return state_->cloud.pts[i]; }

  // Indices of all points within `radius` of q (unordered).
  std::vector<std::size_t> radius(const Point& q, double radius) const {
    std::vector<std::size_t> out;
    if (size() == 0 || !(radius >= 0)) return out;
    // nanoflann keeps distances strictly below its bound; the next double up keeps "<= r^2".
    const double bound = std::nextafter(radius * radius, std::numeric_limits<double>::infinity());
    std::vector<std::pair<std::size_t, double>> hits;
    nanoflann::SearchParams params;
    params.sorted = false;
    state_->index.radiusSearch(q.data(), bound, hits, params);
    out.reserve(hits.size());
    for (const auto& h : hits) out.push_back(h.first);
    return out;
  }

  // Up to k nearest points as (index, squared distance), nearest first.
  std::vector<std::pair<std::size_t, double>> nearest(const Point& q, std::size_t k) const {
    k = std::min(k, size());
    std::vector<std::size_t> idx(k);
    std::vector<double> d2(k);
    if (k > 0) k = state_->index.knnSearch(q.data(), k, idx.data(), d2.data());
    std::vector<std::pair<std::size_t, double>> out(k);
    for (std::size_t i = 0; i < k; ++i) out[i] = {idx[i], d2[i]};
    return out;
  }

 private:
  struct Cloud {  // nanoflann's dataset interface
    std::vector<Point> pts;
    std::size_t kdtree_get_point_count() const { return pts.size(); }
    double kdtree_get_pt(std::size_t i, std::size_t d) const { return pts[i][static_cast<int>(d)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const { return false; }
  };
  using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, Dim, std::size_t>;
  struct State {
    explicit State(std::vector<Point> p) : cloud{std::move(p)}, index(Dim, cloud, {10, nanoflann::KDTreeSingleIndexAdaptorFlags::SkipInitialBuildIndex}) {
      if (!cloud.pts.empty()) index.buildIndex();
    }
    Cloud cloud;
    Index index;
  };
  std::shared_ptr<const State> state_;
};

}  // namespace slide
