#include "frontend/column_detection.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "frontend/circle_fit.h"
#include "frontend/grid_clustering.h"
#include "frontend/point_stats.h"

namespace slide::frontend {

namespace {
// Items at planar positions, bucketed on a 2-D grid for neighbourhood look-ups: counting-sorted
// by cell over the cells of their bounding box (at most kMaxSide a side: the cell grows for
// scattered items), each cell's contiguous and in their given order. Items at non-finite
// positions are left out.
class PlanarBuckets {
 public:
  // n items, item k at xy(k) with id(k).
  template <typename XY, typename Id>
  PlanarBuckets(std::size_t n, XY&& xy, Id&& id, double cell) {
    float x0 = 1e30f, x1 = -1e30f, y0 = 1e30f, y1 = -1e30f;
    for (std::size_t k = 0; k < n; ++k)
      if (const Eigen::Vector2f q = xy(k); q.allFinite()) {
        x0 = std::min(x0, q.x()), x1 = std::max(x1, q.x());
        y0 = std::min(y0, q.y()), y1 = std::max(y1, q.y());
      }
    if (x0 > x1) return;
    cell = std::max({cell, double(x1 - x0) / (kMaxSide - 2), double(y1 - y0) / (kMaxSide - 2)});
    inv_ = 1.0 / cell;
    gx_ = static_cast<long>(std::floor(x0 * inv_)), gy_ = static_cast<long>(std::floor(y0 * inv_));
    nx_ = static_cast<long>(std::floor(x1 * inv_)) - gx_ + 1, ny_ = static_cast<long>(std::floor(y1 * inv_)) - gy_ + 1;
    start_.assign(nx_ * ny_ + 1, 0);
    std::vector<int> cell_of(n, -1);
    for (std::size_t k = 0; k < n; ++k) {
      const Eigen::Vector2f q = xy(k);
      if (!q.allFinite()) continue;
      const long cx = std::clamp(static_cast<long>(std::floor(q.x() * inv_)) - gx_, 0L, nx_ - 1);
      const long cy = std::clamp(static_cast<long>(std::floor(q.y() * inv_)) - gy_, 0L, ny_ - 1);
      cell_of[k] = static_cast<int>(cx * ny_ + cy);
      ++start_[cell_of[k] + 1];
    }
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
    items_.resize(start_.back());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (std::size_t k = 0; k < n; ++k)
      if (cell_of[k] >= 0) items_[fill[cell_of[k]]++] = {xy(k), id(k)};
  }
  // Points of `cloud` (indices `idx`) at their x, y; ids are the indices.
  PlanarBuckets(const Cloud& cloud, const std::vector<int>& idx, double cell)
      : PlanarBuckets(
            idx.size(), [&](std::size_t k) -> Eigen::Vector2f { return cloud[idx[k]].head<2>(); },
            [&](std::size_t k) { return idx[k]; }, cell) {}
  // Calls f(id, squared horizontal distance) for every item within `radius` of c.
  template <typename F>
  void forNear(const Eigen::Vector2d& c, double radius, F&& f) const {
    if (items_.empty()) return;
    const long x0 = std::max(0L, static_cast<long>(std::floor((c.x() - radius) * inv_)) - gx_);
    const long x1 = std::min(nx_ - 1, static_cast<long>(std::floor((c.x() + radius) * inv_)) - gx_);
    const long y0 = std::max(0L, static_cast<long>(std::floor((c.y() - radius) * inv_)) - gy_);
    const long y1 = std::min(ny_ - 1, static_cast<long>(std::floor((c.y() + radius) * inv_)) - gy_);
    const double r2 = radius * radius;
    for (long x = x0; x <= x1; ++x)
      for (long y = y0; y <= y1; ++y)
        for (int k = start_[x * ny_ + y], e = start_[x * ny_ + y + 1]; k < e; ++k) {
          const double dx = items_[k].xy.x() - c.x(), dy = items_[k].xy.y() - c.y(), d2 = dx * dx + dy * dy;
          if (d2 <= r2) f(items_[k].id, d2);
        }
  }

 private:
  static constexpr long kMaxSide = 1024;
  struct Item {
    Eigen::Vector2f xy;
    int id;
  };
  double inv_ = 1.0;
  long gx_ = 0, gy_ = 0, nx_ = 0, ny_ = 0;  // the box's first cell on the global grid, and its size in cells
  std::vector<int> start_;                  // cell c holds items_[start_[c], start_[c + 1])
  std::vector<Item> items_;
};

struct Blob {
  int slice = 0;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double extent = 0;  // largest bounding-box side
  int points = 0;
  std::vector<int> idx;
};

// Small cross-sections of every slice.
std::vector<Blob> sliceBlobs(const Cloud& cloud, const std::vector<std::vector<int>>& slices, const ColumnParams& p) {
  std::vector<Blob> blobs;
  for (std::size_t s = 0; s < slices.size(); ++s) {
    if (slices[s].empty()) continue;
    for (const auto& cl : clusterGrid(cloud, slices[s], {p.cell, true, p.min_blob_points})) {
      float x0 = 1e30f, x1 = -1e30f, y0 = 1e30f, y1 = -1e30f;
      Eigen::Vector2d c = Eigen::Vector2d::Zero();
      for (int i : cl) {
        x0 = std::min(x0, cloud[i].x()), x1 = std::max(x1, cloud[i].x());
        y0 = std::min(y0, cloud[i].y()), y1 = std::max(y1, cloud[i].y());
        c += Eigen::Vector2d(cloud[i].x(), cloud[i].y());
      }
      const double extent = std::max(x1 - x0, y1 - y0);
      if (extent > p.max_diameter) continue;
      blobs.push_back({static_cast<int>(s), c / static_cast<double>(cl.size()), extent, static_cast<int>(cl.size()), cl});
    }
  }
  return blobs;
}

// Groups of blobs in different slices whose centres chain within stack_distance.
std::vector<std::vector<int>> stackBlobs(const std::vector<Blob>& blobs, const std::vector<int>& subset, double dist) {
  // Union-find over positions k in `subset`; the buckets hold positions.
  const PlanarBuckets grid(
      subset.size(), [&](std::size_t k) -> Eigen::Vector2f { return blobs[subset[k]].centre.cast<float>(); },
      [](std::size_t k) { return static_cast<int>(k); }, dist);
  std::vector<int> parent(subset.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t k = 0; k < subset.size(); ++k) {
    const Blob& b = blobs[subset[k]];
    grid.forNear(b.centre, dist, [&](int ko, double) {
      if (ko <= static_cast<int>(k) || blobs[subset[ko]].slice == b.slice) return;
      const int ra = root(static_cast<int>(k)), rb = root(ko);
      if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
    });
  }
  // Stacks numbered in the order of their first blob in `subset`, each sized before it is filled.
  std::vector<int> label(subset.size(), -1), size;
  for (std::size_t k = 0; k < subset.size(); ++k) {
    const int r = root(static_cast<int>(k));
    if (label[r] < 0) label[r] = static_cast<int>(size.size()), size.push_back(0);
    ++size[label[r]];
  }
  std::vector<std::vector<int>> stacks(size.size());
  for (std::size_t s = 0; s < size.size(); ++s) stacks[s].reserve(size[s]);
  for (std::size_t k = 0; k < subset.size(); ++k) stacks[label[root(static_cast<int>(k))]].push_back(subset[k]);
  return stacks;
}

// Whether the cross-sections are arcs: of those wide and dense enough to tell, at least
// min_arc_fraction hold a circle (RANSAC) through most of their points whose radius fits
// their extent. A flat face (wall, pillar) needs a far larger circle; scattered foliage has
// no circle through most of its points.
bool arcShaped(const Cloud& cloud, const std::vector<Blob>& blobs, const std::vector<int>& stack, const ColumnParams& p) {
  int tested = 0, arcs = 0;
  CircleRansacParams rp;
  rp.inlier_distance = p.arc_inlier_distance;
  rp.max_radius = p.max_diameter;
  std::vector<Eigen::Vector2d> xy;
  for (int b : stack) {
    const Blob& bl = blobs[b];
    if (bl.extent < p.arc_min_extent || bl.points < p.arc_min_points) continue;
    xy.clear();
    for (int i : bl.idx) xy.emplace_back(cloud[i].x(), cloud[i].y());
    ++tested;
    const auto c = fitCircleRansac(xy, rp);
    arcs += c && c->inliers >= p.arc_min_inliers * bl.points && c->radius <= p.arc_max_radius_ratio * bl.extent;
  }
  return tested == 0 || arcs >= p.min_arc_fraction * tested;
}

int distinctSlices(const std::vector<Blob>& blobs, const std::vector<int>& stack, int* lo = nullptr, int* hi = nullptr) {
  std::vector<int> s;
  for (int b : stack) s.push_back(blobs[b].slice);
  std::sort(s.begin(), s.end());
  if (lo) *lo = s.empty() ? 0 : s.front();
  if (hi) *hi = s.empty() ? 0 : s.back();
  return static_cast<int>(std::unique(s.begin(), s.end()) - s.begin());
}
}  // namespace

std::vector<Column> detectColumns(const Cloud& cloud, const std::vector<float>& h, const std::vector<int>& above,
                                  const ScanLines& lines, const ColumnParams& p, std::vector<char>& taken,
                                  std::vector<ColumnRejection>* rejected) {
  std::vector<Column> out;
  const int num_slices = std::max(1, static_cast<int>(std::floor((p.slice_high - p.slice_low) / p.slice_height)));
  std::vector<std::vector<int>> slices(num_slices);
  // Highest elevation angle seen (beyond 3 m): columns need not reach above what is visible.
  double tan_elev = -1e9;
  for (int i : above) {
    const double r = std::hypot(cloud[i].x(), cloud[i].y());
    if (r > 3.0) tan_elev = std::max(tan_elev, cloud[i].z() / r);
    const int s = static_cast<int>(std::floor((h[i] - p.slice_low) / p.slice_height));
    if (s >= 0 && s < num_slices) slices[s].push_back(i);
  }
  const PlanarBuckets all(cloud, above, 0.5);
  std::vector<PlanarBuckets> slice_buckets;
  slice_buckets.reserve(num_slices);
  for (const auto& slice : slices) slice_buckets.emplace_back(cloud, slice, 0.5);
  const std::vector<Blob> blobs = sliceBlobs(cloud, slices, p);
  std::vector<char> in_column;
  std::vector<int> every(blobs.size());
  std::iota(every.begin(), every.end(), 0);
  auto reject = [&](const Eigen::Vector2d& c, const std::string& why) {
    if (rejected) rejected->push_back({c, why});
  };

  // Candidate stacks of any small cross-sections; then only the isolated ones count.
  std::vector<std::vector<int>> candidates;
  for (const auto& stack : stackBlobs(blobs, every, p.stack_distance)) {
    if (distinctSlices(blobs, stack) < p.min_slices) continue;
    std::vector<int> isolated;
    for (int b : stack) {
      const Blob& bl = blobs[b];
      // A lone point (a far trunk's one return per beam) could be a sparse face seen at a
      // grazing angle: its ring must be wider, past the face's neighbouring returns.
      const double inner = 0.5 * bl.extent + p.isolation_gap;
      const double outer = inner + (bl.points == 1 ? p.single_point_ring : p.isolation_ring);
      int ring = 0;
      slice_buckets[bl.slice].forNear(bl.centre, outer, [&](int, double d2) { ring += d2 > inner * inner; });
      if (ring <= p.max_ring_fraction * bl.points) isolated.push_back(b);
    }
    bool any = false;
    for (const auto& s : stackBlobs(blobs, isolated, p.stack_distance)) {
      int lo = 0, hi = 0, multi = 0;
      if (distinctSlices(blobs, s, &lo, &hi) < p.min_slices || (hi - lo + 1) * p.slice_height < p.min_span) continue;
      for (int b : s) multi += blobs[b].points > 1;
      if (multi < p.min_multi_point_slices) continue;
      candidates.push_back(s);
      any = true;
    }
    if (!any) reject(blobs[stack.front()].centre, "too few isolated cross-sections (" + std::to_string(isolated.size()) +
                                                       " of " + std::to_string(stack.size()) + ")");
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const std::vector<int>& a, const std::vector<int>& b) { return a.size() > b.size(); });

  for (const auto& stack : candidates) {
    // Axis: weighted least squares of the centres against slice height.
    double sw = 0, sz = 0, szz = 0;
    Eigen::Vector2d sp = Eigen::Vector2d::Zero(), spz = Eigen::Vector2d::Zero();
    std::vector<double> extents;
    for (int b : stack) {
      const Blob& bl = blobs[b];
      const double w = bl.points, z = p.slice_low + (bl.slice + 0.5) * p.slice_height;
      sw += w, sz += w * z, szz += w * z * z, sp += w * bl.centre, spz += w * z * bl.centre;
      extents.push_back(bl.extent);
    }
    if (p.min_arc_fraction > 0 && !arcShaped(cloud, blobs, stack, p)) {
      reject(blobs[stack.front()].centre, "cross-sections are not arcs");
      continue;
    }
    Column col;
    const double det = sw * szz - sz * sz;
    col.slope = det > 1e-9 * sw * sw ? Eigen::Vector2d((sw * spz - sz * sp) / det) : Eigen::Vector2d::Zero();
    col.base = (sp - col.slope * sz) / sw;
    const double z_mid = sz / sw;
    const Eigen::Vector2d mid = col.base + col.slope * z_mid;
    if (std::atan(col.slope.norm()) * 180.0 / M_PI > p.max_lean_deg) {
      reject(mid, "leaning");
      continue;
    }
    col.radius = 0.5 * quantileInPlace(extents, 0.5);
    col.slices = static_cast<int>(stack.size());
    const double reach = col.radius + p.margin;
    double top = 0, ground_z = 0;
    int top_point = -1;
    all.forNear(mid, reach + col.slope.norm() * p.max_height + 0.01, [&](int i, double) {
      if (taken[i] || h[i] > p.max_height) return;
      const Eigen::Vector2d c = col.base + col.slope * h[i];
      if ((Eigen::Vector2d(cloud[i].x(), cloud[i].y()) - c).squaredNorm() > reach * reach) return;
      col.points.push_back(i);
      if (h[i] > top) top = h[i], ground_z = cloud[i].z() - h[i], top_point = i;
    });
    if (static_cast<int>(col.points.size()) < p.min_points) {
      reject(mid, "too few points");
      continue;
    }
    const double ceiling = mid.norm() * tan_elev - ground_z - p.ceiling_margin;
    if (top < std::min(p.min_top, ceiling)) {
      reject(mid, "too short (" + std::to_string(top) + " m)");
      continue;
    }
    if (p.wall.min_fraction > 0) {
      if (in_column.empty()) in_column.assign(cloud.size(), 0);
      for (int i : col.points) in_column[i] = 1;
      const double face = faceFraction(cloud, lines, col.points, in_column, p.wall);
      for (int i : col.points) in_column[i] = 0;
      if (face >= p.wall.min_fraction) {
        reject(mid, "a face seen edge-on (" + std::to_string(face) + " of its beams continue on a line)");
        continue;
      }
    }
    // Canopy: points above min_top spreading well beyond the axis.
    int canopy = 0, high = 0;
    std::vector<double> high_h;
    double view_above = 1e9;  // least height of the view's top above those returns
    all.forNear(mid, p.canopy_radius + 2.0, [&](int i, double d2) {
      if (h[i] < p.min_top) return;
      ++high;
      canopy += d2 > p.canopy_radius * p.canopy_radius;
      high_h.push_back(h[i]);
      view_above = std::min(view_above, cloud[i].head<2>().norm() * tan_elev - cloud[i].z());
    });
    // A flat layer above it (the returns there within ceiling_max_spread of one height) is a
    // ceiling, not a crown: the column is part of a building (a door jamb, a wall's end).
    // Far off, a patch of ceiling gives fewer returns; fewer count when the view reaches above
    // them all (a crown cut off by the top of the view is as flat at its cut).
    int ceiling_points = p.ceiling_min_points;
    if (p.ceiling_full_range > 0 && mid.norm() > p.ceiling_full_range && view_above > p.ceiling_margin) {
      const double thinning = std::pow(p.ceiling_full_range / mid.norm(), 2);
      ceiling_points = std::max(std::min(p.ceiling_min_points_far, p.ceiling_min_points),
                                static_cast<int>(std::ceil(p.ceiling_min_points * thinning)));
    }
    if (p.ceiling_max_spread > 0 && static_cast<int>(high_h.size()) >= ceiling_points) {
      const double lo = quantileInPlace(high_h, 0.1), hi = quantileInPlace(high_h, 0.9);
      if (hi - lo <= p.ceiling_max_spread) {
        reject(mid, "under a flat ceiling (" + std::to_string(high_h.size()) + " returns within " + std::to_string(hi - lo) + " m)");
        continue;
      }
    }
    if (p.ceiling_max_spread > 0 && p.ceiling_min_above > 0) {
      std::vector<float> over = lines.heightsAbove(cloud[top_point], static_cast<float>(mid.norm() - p.margin));
      if (static_cast<int>(over.size()) >= p.ceiling_min_above) {
        std::vector<double> z(over.begin(), over.end());
        const double lo = quantileInPlace(z, 0.1), hi = quantileInPlace(z, 0.9);
        if (hi - lo <= p.ceiling_max_spread && lo >= cloud[top_point].z() - p.ceiling_margin) {
          reject(mid, "under a flat ceiling nearer (" + std::to_string(z.size()) + " returns above its top within " +
                          std::to_string(hi - lo) + " m)");
          continue;
        }
      }
    }
    col.trunk = col.radius >= p.trunk_min_radius ||
                (high > 0 && canopy >= p.canopy_min_fraction * (high + static_cast<int>(col.points.size())));
    if (!col.trunk && (top + p.end_margin >= std::min(ceiling + p.ceiling_margin, p.max_height) ||
                       lines.hiddenAbove(cloud[top_point], static_cast<float>(mid.norm() - p.end_margin))))
      col.confidence = p.unsure_confidence;
    for (int i : col.points) taken[i] = 1;
    out.push_back(std::move(col));
  }
  // Unsure calls follow the sure ones of this scan.
  int sure_trunks = 0, sure_poles = 0;
  for (const Column& c : out)
    if (c.confidence >= 1.0) ++(c.trunk ? sure_trunks : sure_poles);
  for (Column& c : out)
    if (c.confidence < 1.0) c.trunk = sure_trunks > sure_poles;
  return out;
}

}  // namespace slide::frontend
