#include "frontend/geometric_segmenter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <cstdint>
#include <limits>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "frontend/point_stats.h"

namespace slide::frontend {

namespace {
// Horizontal range of the cluster's nearest return.
double nearestRange(const Cloud& cloud, const std::vector<int>& cluster) {
  double r = std::numeric_limits<double>::infinity();
  for (int i : cluster) r = std::min(r, double(cloud[i].head<2>().norm()));
  return r;
}

// Median height of the ground under the points (z minus their height above it, h).
double groundUnder(const Cloud& cloud, const std::vector<float>& h, const std::vector<int>& pts) {
  std::vector<double> g;
  g.reserve(pts.size());
  for (int i : pts) g.push_back(cloud[i].z() - h[i]);
  return quantileInPlace(g, 0.5);
}

struct Footprint {
  double length = 0, width = 0;
};

// The minimum-area rectangle of the cluster's top view. Points strictly inside the octagon of
// the extremes along x, y, x + y and x - y cannot be on the convex hull, so they are dropped
// before OpenCV sorts the rest (Akl-Toussaint); the rectangle is the same. A cluster whose
// bounding box has a side longer than `max_diagonal` fits no rectangle of that diagonal: it gets
// an infinite footprint without a fit.
Footprint footprintOf(const Cloud& cloud, const std::vector<int>& idx,
                      double max_diagonal = std::numeric_limits<double>::infinity()) {
  if (idx.empty()) return {};
  // Extremes in the directions 180, 225, 270, 315, 0, 45, 90, 135 degrees: counter-clockwise.
  std::array<Eigen::Vector2f, 8> ext;
  std::array<float, 8> best;
  best.fill(-std::numeric_limits<float>::infinity());
  for (int i : idx) {
    const float x = cloud[i].x(), y = cloud[i].y();
    const std::array<float, 8> score{-x, -x - y, -y, x - y, x, x + y, y, y - x};
    for (int d = 0; d < 8; ++d)
      if (score[d] > best[d]) best[d] = score[d], ext[d] = {x, y};
  }
  if (std::max(best[4] + best[0], best[6] + best[2]) > max_diagonal)
    return {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  std::array<Eigen::Vector2f, 8> from, normal;  // inner normals of the octagon's proper edges
  int edges = 0;
  for (int d = 0; d < 8; ++d) {
    const Eigen::Vector2f e = ext[(d + 1) % 8] - ext[d];
    if (e.squaredNorm() == 0) continue;
    from[edges] = ext[d];
    normal[edges++] = {-e.y(), e.x()};
  }
  std::vector<cv::Point2f> pts;
  pts.reserve(idx.size());
  for (int i : idx) {
    const Eigen::Vector2f p(cloud[i].x(), cloud[i].y());
    bool inside = edges >= 3;
    for (int k = 0; k < edges && inside; ++k) inside = normal[k].dot(p - from[k]) > 1e-4f * normal[k].norm();
    if (!inside) pts.emplace_back(p.x(), p.y());
  }
  const cv::RotatedRect r = cv::minAreaRect(pts);
  return {std::max(r.size.width, r.size.height), std::min(r.size.width, r.size.height)};
}

// |r(i-1) - 2 r(i) + r(i+1)| over the scan-order triplets of the points marked `label` whose
// neighbours lie within 0.5 m.
std::vector<double> secondDifferences(const Cloud& cloud, const std::vector<int>& idx, std::vector<int>& mark, int label) {
  for (int i : idx) mark[i] = label;
  std::vector<double> d;
  const int n = static_cast<int>(cloud.size());
  for (int i : idx) {
    if (i == 0 || i + 1 >= n || mark[i - 1] != label || mark[i + 1] != label) continue;
    if ((cloud[i - 1] - cloud[i]).squaredNorm() > 0.25f || (cloud[i + 1] - cloud[i]).squaredNorm() > 0.25f) continue;
    d.push_back(std::abs(double(cloud[i - 1].norm()) - 2.0 * cloud[i].norm() + cloud[i + 1].norm()));
  }
  return d;
}

// Median second difference of ranges over consecutive scan-order triplets in the cluster;
// NaN when there are too few.
double roughness(const Cloud& cloud, const std::vector<int>& idx, std::vector<int>& mark, int label) {
  std::vector<double> d = secondDifferences(cloud, idx, mark, label);
  return d.size() < 10 ? std::nan("") : quantileInPlace(d, 0.5);
}

std::int64_t cellKey(const Eigen::Vector3f& p, double inv_cell) {
  return (static_cast<std::int64_t>(std::floor(p.x() * inv_cell)) << 32) ^
         (static_cast<std::int64_t>(std::floor(p.y() * inv_cell)) & 0xffffffffLL);
}

// Share of the cluster's planar cells that also hold one of the `over` cells.
double coveredFraction(const Cloud& cloud, const std::vector<int>& idx, const std::unordered_set<std::int64_t>& over,
                       double inv_cell) {
  std::unordered_set<std::int64_t> cells;
  for (int i : idx) cells.insert(cellKey(cloud[i], inv_cell));
  int covered = 0;
  for (std::int64_t c : cells) covered += over.count(c) > 0;
  return cells.empty() ? 0.0 : static_cast<double>(covered) / cells.size();
}

double quantileOf(const std::vector<float>& values, const std::vector<int>& idx, double q) {
  std::vector<double> v;
  v.reserve(idx.size());
  for (int i : idx) v.push_back(values[i]);
  return quantileInPlace(v, q);
}

// Longer side of the cluster's axis-aligned bounding box in x-y.
double boxSide(const Cloud& cloud, const std::vector<int>& idx) {
  Eigen::Vector2f lo = Eigen::Vector2f::Constant(std::numeric_limits<float>::max()), hi = -lo;
  for (int i : idx) lo = lo.cwiseMin(cloud[i].head<2>()), hi = hi.cwiseMax(cloud[i].head<2>());
  return idx.empty() ? 0.0 : static_cast<double>((hi - lo).maxCoeff());
}

// Marks in `cut` the points that stand under a return at the top of the view (ViewCutParams).
void markViewCut(const ScanLines& lines, const ViewCutParams& p, std::vector<char>& cut) {
  const auto top = lines.viewTop(p.tolerance_deg, p.min_share, p.max_origin_height);
  if (!top) return;
  lines.markUnderTop(*top, p.tolerance_deg, static_cast<float>(p.range_tolerance), cut);
}

// Whether a cluster floats: its bottom hidden by nearer returns, and the ground estimated under
// it well above the ground under them (CarParams::max_hidden_bottom).
bool floats(const Cloud& cloud, const std::vector<float>& h, const std::vector<int>& cl, const ScanLines& lines,
            const CarParams& kp) {
  int bins = 0;
  const double ground = groundUnder(cloud, h, cl);
  const std::vector<int> hiding = lines.hiddenBelow(cl, static_cast<float>(kp.hidden_below),
                                                    static_cast<float>(kp.hidden_margin), bins, static_cast<float>(ground));
  if (hiding.empty() || static_cast<int>(hiding.size()) <= kp.max_hidden_bottom * bins) return false;
  return ground - groundUnder(cloud, h, hiding) > kp.max_ground_rise;
}

// Whether the cluster's ground estimate (h: height above it) lies above the ground seen nearest
// to it (CarParams::seen_ground_search).
bool aboveSeenGround(const Cloud& cloud, const std::vector<float>& h, const std::vector<int>& cl,
                     const SeenGround& seen, double cell, const CarParams& kp) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (int i : cl) c += cloud[i].head<2>().cast<double>();
  c /= static_cast<double>(cl.size());
  double radius = 0;
  for (int i : cl) radius = std::max(radius, (cloud[i].head<2>().cast<double>() - c).norm());
  const double own = groundUnder(cloud, h, cl);
  // Cells by distance from the cluster's edge, from 1 m out (its own cells and the window that
  // set its ground) to seen_ground_search: the nearest that saw the ground decide.
  const int reach = static_cast<int>(std::ceil((radius + kp.seen_ground_search) / cell));
  // Distances in squared cells from the centre: from (radius + 1 m)^2 to (radius + search)^2.
  const double lo = std::pow((radius + 1.0) / cell, 2), hi = std::pow((radius + kp.seen_ground_search) / cell, 2);
  double best = std::numeric_limits<double>::infinity();
  float best_z = 0;
  for (int v = -reach; v <= reach; ++v)
    for (int u = -reach; u <= reach; ++u) {
      const double d2 = static_cast<double>(u * u + v * v);
      if (d2 < lo || d2 > hi || d2 >= best) continue;
      const float z = seen.at(c.x() + u * cell, c.y() + v * cell);
      if (std::isfinite(z)) best = d2, best_z = z;
    }
  if (!std::isfinite(best)) return false;
  const double d = std::sqrt(best) * cell - radius;
  return own - best_z > kp.seen_ground_rise + kp.seen_ground_slope * d;
}

// The scan's own range noise floor: the 25th percentile of the second differences over the
// scan-order triplets of returns above the ground (GeometricSegmenterParams::roughness_floor_factor);
// NaN with fewer than 100 triplets.
double rangeNoiseFloor(const Cloud& cloud, const std::vector<int>& above) {
  std::vector<int> mark(cloud.size(), -1);
  std::vector<double> d = secondDifferences(cloud, above, mark, 0);
  return d.size() < 100 ? std::nan("") : quantileInPlace(d, 0.25);
}

// Step 2: clusters of the untaken points `above` (h: height above ground) below the height
// cap that fit a car (module comment in the header) and are not the rest of a stack the view
// cuts off (beside the points marked in `cut`); their points are marked taken.
std::vector<std::vector<int>> carClusters(const Cloud& cloud, const std::vector<float>& h, const std::vector<int>& above,
                                          const ScanLines& lines, const std::vector<char>& cut, const SeenGround& seen,
                                          const GeometricSegmenterParams& params, double roughness_cap, std::vector<char>& taken) {
  const CarParams& kp = params.car;
  const bool any_cut = params.view_cut.max_beside_share < 1 && std::find(cut.begin(), cut.end(), 1) != cut.end();
  std::vector<int> low;
  std::unordered_set<std::int64_t> over;  // cells with returns just above the cap
  for (int i : above) {
    if (!taken[i] && h[i] <= kp.height_cap) low.push_back(i);
    else if (kp.max_covered < 1 && h[i] > kp.height_cap && h[i] <= kp.height_cap + kp.cover_height)
      over.insert(cellKey(cloud[i], 1.0 / kp.cell));
  }
  std::vector<std::vector<int>> cars;
  if (low.empty()) return cars;
  std::vector<int> mark(cloud.size(), -1);
  int label = 0;
  // A cluster too long or wide for one car, but no longer than max_split_length (a wall's or
  // hedge's base is), is re-clustered on finer cells (down to min_split_cell): cars parked side
  // by side or back to back with gaps of a few decimetres join at `cell`; each part is then
  // tested as a cluster of its own.
  std::vector<std::pair<std::vector<int>, double>> todo;  // cluster, the cell it was clustered on
  const int fewest = std::min(kp.min_points, kp.min_points_far);
  // The returns a car at horizontal range r gives at least (CarParams::min_points_far).
  auto needed = [&](double r) {
    if (r <= kp.near_range) return kp.min_points;
    return std::max(fewest, static_cast<int>(std::ceil(kp.min_points * kp.near_range * kp.near_range / (r * r))));
  };
  for (auto& cl : clusterGrid(cloud, low, {kp.cell, false, fewest})) todo.emplace_back(std::move(cl), kp.cell);
  for (std::size_t k = 0; k < todo.size(); ++k) {
    std::vector<int> cl = std::move(todo[k].first);
    const double cell = todo[k].second;
    if (auto parts = splitAtNotch(cloud, cl, kp.notch)) {
      for (auto* part : {&parts->first, &parts->second})
        if (static_cast<int>(part->size()) >= fewest) todo.emplace_back(std::move(*part), cell);
      continue;
    }
    const double range = nearestRange(cloud, cl);
    if (static_cast<int>(cl.size()) < needed(range)) continue;
    const double rough = kp.max_roughness > 0 ? roughness(cloud, cl, mark, label++) : std::nan("");
    if (rough > std::min(kp.max_roughness, roughness_cap)) continue;
    // Fewer returns than min_points pass only with a face shown smooth (far cars do; a bush's
    // scattered returns give too few scan-order triplets to measure).
    if (kp.max_roughness > 0 && std::isnan(rough) && static_cast<int>(cl.size()) < kp.min_points &&
        !(kp.max_edge_spread > 0 && edgeSpread(cloud, cl) <= kp.max_edge_spread))
      continue;
    const double top = quantileOf(h, cl, 0.95), bottom = quantileOf(h, cl, 0.05);
    if (top < kp.min_top || top > kp.max_top || bottom > kp.max_bottom) continue;
    if (kp.max_range > 0 && range > kp.max_range) continue;
    const Footprint f = footprintOf(cloud, cl, std::hypot(kp.max_length, kp.max_width));
    if (f.length > kp.max_length || f.width > kp.max_width) {
      if (0.5 * cell >= kp.min_split_cell - 1e-9 && boxSide(cloud, cl) <= kp.max_split_length)
        for (auto& part : clusterGrid(cloud, cl, {0.5 * cell, false, fewest})) todo.emplace_back(std::move(part), 0.5 * cell);
      continue;
    }
    if (f.length < kp.min_length) continue;
    // Car-sized, but falling apart on gap_cell cells into two or more parts of at least
    // min_points (the end face of a car and a stripe of the next one's side, seen through the gap
    // between them, join on `cell`): each part is tested as a cluster of its own. Clustered on
    // the footprint, as the gap between two cars is a vertical slot and a far car's faces must
    // not fall into one strip per beam.
    const double gap = std::max(kp.gap_cell, range * kp.gap_angle_deg * M_PI / 180.0);
    if (kp.gap_cell > 0 && cell > gap + 1e-9) {
      auto parts = clusterGrid(cloud, cl, {gap, true, kp.gap_min_points});
      if (parts.size() >= 2) {
        for (auto& part : parts) todo.emplace_back(std::move(part), gap);
        continue;
      }
    }
    if (any_cut) {
      int beside = 0;
      for (int i : cl) beside += lines.besideMarked(cloud[i], cut, static_cast<float>(params.view_cut.beside_range));
      if (beside > params.view_cut.max_beside_share * cl.size()) continue;
    }
    if (kp.max_covered < 1 && coveredFraction(cloud, cl, over, 1.0 / kp.cell) > kp.max_covered) continue;
    if (kp.max_hidden_bottom < 1 && floats(cloud, h, cl, lines, kp)) continue;
    if (kp.seen_ground_search > 0 && aboveSeenGround(cloud, h, cl, seen, params.ground.cell, kp)) continue;
    for (int i : cl) taken[i] = 1;
    cars.push_back(std::move(cl));
  }
  return cars;
}

// A face goes on past a cluster when the next beam beyond its top or bottom, within this
// elevation window, returns within this horizontal range of the end's: an upright face's
// returns keep their range to within the range noise and its tilt over one beam step.
constexpr float kContinuedRangeTolerance = 0.15f;
constexpr double kContinuedWindowDeg = 2.0;

// Step 3: clusters of the untaken points `above` whose extents fit `other`, that stand low,
// are squat and solid and, when they could be the seen part of something larger (as tall as a
// car, `hidden_min_height`, or as thin as a face), are seen whole; a long one that falls into
// big pieces on finer cells counts as those pieces (furniture standing centimetres apart).
std::vector<std::vector<int>> otherClusters(const Cloud& cloud, const std::vector<float>& h, const std::vector<int>& above,
                                            const ScanLines& lines, const GeometricSegmenterParams& p,
                                            const ClassInfo& other, double hidden_min_height, double roughness_cap,
                                            const std::vector<char>& taken) {
  std::vector<int> rest;
  for (int i : above)
    if (!taken[i]) rest.push_back(i);
  std::vector<std::vector<int>> out;
  if (rest.empty()) return out;
  std::vector<int> mark(cloud.size(), -1);
  std::vector<char> in_cluster(cloud.size(), 0);
  int label = 0;
  const double max_height = p.other_max_height > 0 ? std::min(p.other_max_height, other.size_max.z()) : other.size_max.z();
  const double max_diagonal = std::hypot(other.size_max.x(), other.size_max.y());
  // Height (2nd-98th percentile above ground) when the cluster stands like an "other": its
  // height fits the class, its bottom is low; nullopt otherwise.
  auto standingHeight = [&](const std::vector<int>& cl) -> std::optional<double> {
    const double bottom = quantileOf(h, cl, 0.02), height = quantileOf(h, cl, 0.98) - bottom;
    if (height > max_height || height < other.size_min.z() || bottom > p.other_max_bottom) return std::nullopt;
    return height;
  };
  struct Candidate {
    std::vector<int> points;
    double height;
    Footprint footprint;
  };
  std::vector<Candidate> todo;
  // Cells half as large: pieces of furniture standing centimetres apart fall apart.
  const GridClusterParams fine{0.5 * p.other_cluster.cell, false, 1};
  for (auto& cl : clusterGrid(cloud, rest, p.other_cluster)) {
    const std::optional<double> height = standingHeight(cl);
    if (!height) continue;
    const Footprint f = footprintOf(cloud, cl, max_diagonal);
    // A long cluster may be several pieces: it is split when at least two parts of
    // other_split_min_points hold 90 % of its points, not when it crumbles into scraps (far
    // off, a LiDAR's beams lie farther apart than the finer cells).
    std::vector<std::vector<int>> parts;
    if (p.other_split_length > 0 && f.length > p.other_split_length) {
      parts = clusterGrid(cloud, cl, fine);
      std::size_t kept = 0;
      parts.erase(std::remove_if(parts.begin(), parts.end(),
                                 [&](const std::vector<int>& part) {
                                   return static_cast<int>(part.size()) < p.other_split_min_points;
                                 }),
                  parts.end());
      for (const auto& part : parts) kept += part.size();
      if (kept < 0.9 * cl.size()) parts.clear();
    }
    if (parts.size() < 2) {
      todo.push_back({std::move(cl), *height, f});
      continue;
    }
    for (auto& part : parts)
      if (const std::optional<double> part_height = standingHeight(part)) {
        const Footprint part_f = footprintOf(cloud, part, max_diagonal);
        todo.push_back({std::move(part), *part_height, part_f});
      }
  }
  for (auto& [cl, height, f] : todo) {
    if (f.length > other.size_max.x() || f.width > other.size_max.y()) continue;
    if (p.other_not_column && height >= p.column.min_top && f.length <= p.column.max_diameter) continue;
    if (p.other_max_slenderness > 0 && height > p.other_max_slenderness * f.length) continue;
    if (p.other_max_roughness > 0 && roughness(cloud, cl, mark, label++) > std::min(p.other_max_roughness, roughness_cap)) continue;
    const bool may_be_part = p.other_face_max_width <= 0 || height >= hidden_min_height || f.width < p.other_face_max_width;
    if (p.other_max_occluded < 1 && may_be_part) {
      for (int i : cl) in_cluster[i] = 1;
      const double occluded = occludedFraction(cloud, lines, cl, in_cluster, p.occlusion);
      for (int i : cl) in_cluster[i] = 0;
      if (occluded > p.other_max_occluded) continue;
    }
    // Its face goes on past its top or bottom (returns taken by earlier steps or cut off with
    // the top of the view are of unknown extent: they do not count).
    if (p.other_max_continued < 1) {
      for (int i : cl) in_cluster[i] = 1;
      const double continued = lines.continuedFraction(cl, in_cluster, taken, kContinuedRangeTolerance, kContinuedWindowDeg);
      for (int i : cl) in_cluster[i] = 0;
      if (continued > p.other_max_continued) continue;
    }
    out.push_back(std::move(cl));
  }
  return out;
}
}  // namespace

double edgeSpread(const Cloud& cloud, const std::vector<int>& idx) {
  if (idx.size() < 3) return 0.0;
  // Headings 0-88 deg in 2-deg steps: the bounding rectangle at each, the smallest median (an L
  // of two faces lies on two edges of the rectangle along them; the minimum-area rectangle of an
  // L lies across its diagonal).
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> u(idx.size()), v(idx.size()), d(idx.size());
  for (int step = 0; step < 45; ++step) {
    const double a = step * 2.0 * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
    double u0 = 1e30, u1 = -1e30, v0 = 1e30, v1 = -1e30;
    for (std::size_t k = 0; k < idx.size(); ++k) {
      const Eigen::Vector3f& p = cloud[idx[k]];
      u[k] = c * p.x() + s * p.y();
      v[k] = -s * p.x() + c * p.y();
      u0 = std::min(u0, u[k]), u1 = std::max(u1, u[k]), v0 = std::min(v0, v[k]), v1 = std::max(v1, v[k]);
    }
    for (std::size_t k = 0; k < idx.size(); ++k) d[k] = std::min(std::min(u[k] - u0, u1 - u[k]), std::min(v[k] - v0, v1 - v[k]));
    best = std::min(best, quantileInPlace(d, 0.5));
  }
  return best;
}

GeometricSegmenter::GeometricSegmenter(ClassTable classes, GeometricSegmenterParams params)
    : classes_(std::move(classes)), params_(params) {
  for (int id : {params_.trunk_class, params_.pole_class, params_.car_class, params_.other_class}) classes_.at(id);
}

std::vector<Instance> GeometricSegmenter::segment(const io::LabelledScan& scan, InputIssues& issues) const {
  return segment(scan, issues, nullptr);
}

std::vector<Instance> GeometricSegmenter::segment(const io::LabelledScan& scan, InputIssues& issues,
                                                  std::vector<ColumnRejection>* rejected) const {
  if (scan.size() == 0) {
    issues.count("empty scan");
    return {};
  }
  const Cloud& cloud = scan.xyz;
  long bad = 0;
  for (const auto& p : cloud) bad += !p.allFinite();
  issues.count("non-finite point", bad);

  GroundParams gp = params_.ground;
  gp.max_range = params_.max_range;
  SeenGround seen;
  const std::vector<float> h = heightAboveGround(cloud, gp, &seen);
  std::vector<int> above;
  above.reserve(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (std::isfinite(h[i]) && h[i] > gp.threshold) above.push_back(static_cast<int>(i));

  std::vector<Instance> out;
  auto emit = [&](int class_id, const std::vector<int>& idx, double confidence = 1.0) {
    Instance inst;
    inst.id = static_cast<int>(out.size()) + 1;
    inst.class_id = class_id;
    inst.confidence = static_cast<float>(confidence);
    inst.points.reserve(idx.size());
    for (int i : idx) inst.points.push_back(cloud[i]);
    out.push_back(std::move(inst));
  };
  std::vector<char> taken(cloud.size(), 0);
  const ScanLines lines(cloud, above);

  // 1. Columns (trunks, poles).
  for (const Column& c : detectColumns(cloud, h, above, lines, params_.column, taken, rejected))
    emit(c.trunk ? params_.trunk_class : params_.pole_class, c.points, c.confidence);

  // Stacks reaching the top of the view are of unknown height: no car, no other (ViewCutParams).
  std::vector<char> cut(cloud.size(), 0);
  if (params_.view_cut.tolerance_deg > 0) markViewCut(lines, params_.view_cut, cut);
  for (std::size_t i = 0; i < cloud.size(); ++i) taken[i] |= cut[i];

  // 2. Cars, 3. other.
  // Each car carries the cells near it that lines of sight passed through in a car body's height
  // band: its box is not completed over them (a hidden end lies where the view was blocked, not
  // where it went through).
  // Roughness limits follow the sensor's range noise where it is lower than the limits assume.
  double roughness_cap = std::numeric_limits<double>::infinity();
  if (params_.roughness_floor_factor > 0) {
    const double floor = rangeNoiseFloor(cloud, above);
    if (std::isfinite(floor)) roughness_cap = std::max(params_.roughness_cap_min, params_.roughness_floor_factor * floor);
  }
  const std::vector<std::vector<int>> cars = carClusters(cloud, h, above, lines, cut, seen, params_, roughness_cap, taken);
  std::optional<FreeSpace> free;
  if (!cars.empty() && params_.free_space.cell > 0) free.emplace(cloud, params_.free_space);
  const double reach = classes_.at(params_.car_class).typicalSize().x();
  for (const auto& cl : cars) {
    emit(params_.car_class, cl);
    if (!free) continue;
    out.back().free_space = free->near(cl, static_cast<float>(groundUnder(cloud, h, cl)), reach);
  }
  if (params_.emit_other)
    for (const auto& cl : otherClusters(cloud, h, above, lines, params_, classes_.at(params_.other_class),
                                        classes_.at(params_.car_class).size_min.z(), roughness_cap, taken))
      emit(params_.other_class, cl, params_.other_confidence);
  return out;
}

}  // namespace slide::frontend
