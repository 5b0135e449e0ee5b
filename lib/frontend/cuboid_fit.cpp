#include <cmath>
#include <opencv2/imgproc.hpp>
#include <unordered_set>

#include "frontend/point_stats.h"
#include "frontend/shape_fit.h"

namespace slide::frontend {

namespace {
void setWhy(std::string* why, const std::string& s) {
  if (why) *why = s;
}

// Footprint thinned to one point per grid cell, for the rectangle search.
std::vector<cv::Point2f> thinFootprint(const Cloud& pts, double cell) {
  std::unordered_set<std::int64_t> seen;
  std::vector<cv::Point2f> out;
  for (const auto& q : pts) {
    const std::int64_t ix = static_cast<std::int64_t>(std::floor(q.x() / cell));
    const std::int64_t iy = static_cast<std::int64_t>(std::floor(q.y() / cell));
    if (seen.insert((ix << 32) ^ (iy & 0xffffffff)).second) out.emplace_back(q.x(), q.y());
  }
  return out;
}

// Closeness of the footprint to the edges of its bounding rectangle at heading `a`: the sum
// of the points' inverse distances to the nearest edge, each capped at distance `floor`.
double edgeScore(const std::vector<cv::Point2f>& foot, double a, double floor, std::vector<double>& u,
                 std::vector<double>& v) {
  const double c = std::cos(a), s = std::sin(a);
  double u0 = 1e30, u1 = -1e30, v0 = 1e30, v1 = -1e30;
  for (std::size_t i = 0; i < foot.size(); ++i) {
    u[i] = c * foot[i].x + s * foot[i].y;
    v[i] = -s * foot[i].x + c * foot[i].y;
    u0 = std::min(u0, u[i]), u1 = std::max(u1, u[i]), v0 = std::min(v0, v[i]), v1 = std::max(v1, v[i]);
  }
  double score = 0;
  for (std::size_t i = 0; i < foot.size(); ++i) {
    const double d = std::min(std::min(u[i] - u0, u1 - u[i]), std::min(v[i] - v0, v1 - v[i]));
    score += 1.0 / std::max(d, floor);
  }
  return score;
}

// Heading of a footprint's rectangle by search over [0, 90) deg maximizing the closeness of
// the points to the nearest rectangle edge (robust for the L-shaped views of partly seen
// cars, where the minimum-area rectangle aligns with the diagonal). The search caps each
// point's weight at the footprint's cell `cell` (nearer is not resolved; a finer cap lets the
// noisy faces of RGBD views tilt the rectangle by tens of degrees), then refines within three
// steps of the best heading with a cap of 0.4 cells.
double footprintYaw(const std::vector<cv::Point2f>& foot, double step, double cell) {
  if (foot.size() < 3) return 0.0;
  if (step <= 0) {
    cv::Point2f corners[4];
    cv::minAreaRect(foot).points(corners);
    return std::atan2(corners[1].y - corners[0].y, corners[1].x - corners[0].x);
  }
  std::vector<double> u(foot.size()), v(foot.size());
  double coarse = 0, best_score = -1;
  for (double a = 0; a < M_PI / 2; a += step) {
    const double score = edgeScore(foot, a, cell, u, v);
    if (score > best_score) best_score = score, coarse = a;
  }
  double best_yaw = coarse;
  best_score = -1;
  for (int k = -3; k <= 3; ++k) {
    const double a = coarse + k * step;
    const double score = edgeScore(foot, a, 0.4 * cell, u, v);
    if (score > best_score) best_score = score, best_yaw = a;
  }
  return best_yaw;
}

// Extends [lo, hi] to `len` when it is shorter than `min_len` (too short to be the whole
// extent: part of the object went unseen). By default it grows away from the viewpoint
// coordinate `v`; it is placed elsewhere along the axis when that covers at least `min_gain`
// fewer of the cells seen empty (`free_along`: their coordinates on this axis; the nearest
// such placement to the default, in steps of `step` metres).
void completeInterval(double& lo, double& hi, double min_len, double len, double v, std::vector<double> free_along,
                      int min_gain, double step) {
  if (hi - lo >= min_len) return;
  const double slack = len - (hi - lo);
  const double start_default = v <= 0.5 * (lo + hi) ? lo : hi - len;
  double best = start_default;
  if (min_gain > 0 && !free_along.empty() && slack > 0 && step > 0) {
    std::sort(free_along.begin(), free_along.end());
    auto covered = [&](double a) {
      return static_cast<int>(std::upper_bound(free_along.begin(), free_along.end(), a + len) -
                              std::lower_bound(free_along.begin(), free_along.end(), a));
    };
    const int base_n = covered(start_default);
    int best_n = base_n;
    for (double t = 0; t <= slack + 1e-9; t += step) {
      const double a = hi - len + t;  // from grown wholly below lo ... to wholly above hi
      const int n = covered(a);
      if (base_n - n >= min_gain && (n < best_n || (n == best_n && std::abs(a - start_default) < std::abs(best - start_default))))
        best_n = n, best = a;
    }
  }
  lo = best, hi = best + len;
}

// Whether the longer of the two visible horizontal extents is the object's width. It is the
// length, unless it fits the class width but is too short for a length while the other extent
// is too short for a width: then a lone end face is seen (a car's front or rear, from a
// parking aisle) and the length runs along the other axis, hidden. (When both extents could
// be the width, the longer is taken as the length: tried the one nearer the typical width,
// and the one across the line of sight; both gave more duplicate cars in the urban world.)
bool longerExtentIsWidth(double longer, double shorter, const Eigen::Vector3d& size_min,
                         const Eigen::Vector3d& size_max, double tol) {
  if (longer >= size_min.x() || longer > size_max.y() * tol || longer < size_min.y()) return false;
  return shorter < size_min.y();
}
}  // namespace

std::optional<Cuboid> fitCuboid(const Cloud& pts, const CuboidFitParams& p, const Eigen::Vector3d& viewpoint,
                                const Eigen::Vector3d& size_min, const Eigen::Vector3d& size_max,
                                const Eigen::Vector3d& size_typical, std::string* why,
                                std::optional<Cuboid>* other_reading, const Cloud* free_space) {
  if (other_reading) other_reading->reset();
  if (static_cast<int>(pts.size()) < p.min_points) {
    setWhy(why, "too few points (" + std::to_string(pts.size()) + ")");
    return std::nullopt;
  }
  const std::vector<cv::Point2f> foot = thinFootprint(pts, p.footprint_cell);
  const double yaw = footprintYaw(foot, p.yaw_step_deg * M_PI / 180.0, p.footprint_cell);
  // Robust extents along the rectangle's axes and in z.
  std::vector<double> zs;
  for (const auto& q : pts) zs.push_back(q.z());
  const double top_z = quantileInPlace(zs, p.high_percentile), bottom_z = quantileInPlace(zs, p.low_percentile);
  auto extents = [&](double a, double& lo_u, double& hi_u, double& lo_v, double& hi_v, double below = 1e30) {
    const double c = std::cos(a), s = std::sin(a);
    std::vector<double> u, v;
    u.reserve(pts.size());
    v.reserve(pts.size());
    for (const auto& q : pts) {
      if (q.z() > below) continue;
      u.push_back(c * q.x() + s * q.y());
      v.push_back(-s * q.x() + c * q.y());
    }
    if (u.empty()) {
      lo_u = hi_u = lo_v = hi_v = 0;
      return 0;
    }
    lo_u = quantileInPlace(u, p.low_percentile);
    hi_u = quantileInPlace(u, p.high_percentile);
    lo_v = quantileInPlace(v, p.low_percentile);
    hi_v = quantileInPlace(v, p.high_percentile);
    return static_cast<int>(u.size());
  };
  double lo_u, hi_u, lo_v, hi_v;
  extents(yaw, lo_u, hi_u, lo_v, hi_v);
  const double longer = std::max(hi_u - lo_u, hi_v - lo_v);
  if (longer < p.min_visible_fraction * size_min.x()) {
    setWhy(why, "visible length " + std::to_string(longer) + " m too short");
    return std::nullopt;
  }
  // Which face is seen is judged on the lower half of the points: the vertical faces, without
  // the top (a hood or roof seen from above adds depth whichever face is in view).
  double su0, su1, sv0, sv1;
  if (extents(yaw, su0, su1, sv0, sv1, 0.5 * (bottom_z + top_z)) < p.min_points)
    su0 = lo_u, su1 = hi_u, sv0 = lo_v, sv1 = hi_v;
  const double face_u = su1 - su0, face_v = sv1 - sv0;
  const bool end_view =
      longerExtentIsWidth(std::max(face_u, face_v), std::min(face_u, face_v), size_min, size_max, p.size_tolerance);
  const bool length_along_u = (face_u >= face_v) != end_view;

  // The box with its length (x) along heading yaw_x, or nullopt when the extents do not fit the class.
  auto boxAlong = [&](double yaw_x, std::string* reason) -> std::optional<Cuboid> {
    double lu = lo_u, hu = hi_u, lv = lo_v, hv = hi_v;  // the extents at `yaw`, measured above
    if (yaw_x != yaw) extents(yaw_x, lu, hu, lv, hv);
    double lo_z = bottom_z, hi_z = top_z;
    const Eigen::Vector3d observed(hu - lu, hv - lv, hi_z - lo_z);
    if ((observed.array() > size_max.array() * p.size_tolerance).any()) {
      setWhy(reason, "extents (" + std::to_string(observed.x()) + ", " + std::to_string(observed.y()) + ", " +
                         std::to_string(observed.z()) + ") exceed the class maximum");
      return std::nullopt;
    }
    // Extents too short for the class were partly hidden: they grow to the class's typical size,
    // away from the sensor (the bottom is what goes unseen in z). Extents within the class range
    // may be whole and are kept.
    const double c = std::cos(yaw_x), s = std::sin(yaw_x);
    const double view_u = c * viewpoint.x() + s * viewpoint.y(), view_v = -s * viewpoint.x() + c * viewpoint.y();
    if (p.face_band > 0) {
      // Near edges that are faces: the median of the face's returns.
      auto faceEdge = [&](bool along_u, double& lo, double& hi, double view) {
        const bool near_lo = view <= 0.5 * (lo + hi);
        const double edge = near_lo ? lo : hi;
        std::vector<double> at;
        double a0 = 1e30, a1 = -1e30;
        for (const auto& q : pts) {
          const double u = c * q.x() + s * q.y(), v = -s * q.x() + c * q.y();
          const double along = along_u ? u : v, across = along_u ? v : u;
          if (std::abs(along - edge) > p.face_band) continue;
          at.push_back(along);
          a0 = std::min(a0, across), a1 = std::max(a1, across);
        }
        if (at.size() < 5 || a1 - a0 < p.face_min_span) return;
        const double m = quantileInPlace(at, 0.5);
        (near_lo ? lo : hi) = m;
      };
      faceEdge(true, lu, hu, view_u);
      faceEdge(false, lv, hv, view_v);
    }
    const double min_u = std::max(size_min.x(), p.complete_fraction * size_typical.x());
    const double min_v = std::max(size_min.y(), p.complete_fraction * size_typical.y());
    // The cells seen empty across each axis's extent (free_space), by their coordinate along it.
    std::vector<double> free_u, free_v;
    auto freeAlong = [&](bool along_u, double a0, double a1, std::vector<double>& out) {
      out.clear();
      if (!free_space) return;
      for (const auto& q : *free_space) {
        const double u = c * q.x() + s * q.y(), v = -s * q.x() + c * q.y();
        const double across = along_u ? v : u;
        if (across >= a0 && across <= a1) out.push_back(along_u ? u : v);
      }
    };
    // The length is placed across the width completed away from the viewpoint, the width across
    // the length so placed.
    double wv0 = lv, wv1 = hv;
    completeInterval(wv0, wv1, min_v, size_typical.y(), view_v, {}, 0, 0);
    freeAlong(true, wv0, wv1, free_u);
    completeInterval(lu, hu, min_u, size_typical.x(), view_u, free_u, p.free_cells_to_move, p.free_step);
    freeAlong(false, lu, hu, free_v);
    completeInterval(lv, hv, min_v, size_typical.y(), view_v, free_v, p.free_cells_to_move, p.free_step);
    if (hi_z - lo_z < size_min.z()) lo_z = hi_z - size_typical.z();
    const double cu = 0.5 * (lu + hu), cv_ = 0.5 * (lv + hv);
    Cuboid box;
    box.pose = poseFromXyzYaw(c * cu - s * cv_, s * cu + c * cv_, 0.5 * (lo_z + hi_z), wrapAngle(yaw_x));
    box.dims = Eigen::Vector3d(hu - lu, hv - lv, hi_z - lo_z);
    return box;
  };
  double yaw_x = length_along_u ? yaw : yaw + M_PI / 2;
  std::optional<Cuboid> box = boxAlong(yaw_x, why);
  // The faces misjudged (a lone end face in the lower half, the side's sparse returns above it):
  // the length too wide for the class lies along the other axis.
  if (!box)
    if ((box = boxAlong(yaw_x + M_PI / 2, nullptr))) yaw_x += M_PI / 2;
  // No face was long enough to be the length: the length may run along either axis.
  if (box && other_reading && std::max(face_u, face_v) < size_min.x())
    *other_reading = boxAlong(yaw_x + M_PI / 2, nullptr);
  if (box && other_reading && *other_reading && free_space && p.free_cells_to_swap > 0) {
    auto freeIn = [&](const Cuboid& b) {  // cells inside the box's footprint
      const Pose T_box_points = b.pose.inverse();
      int n = 0;
      for (const auto& q : *free_space) {
        const Eigen::Vector3d l = T_box_points * q.cast<double>();
        n += std::abs(l.x()) <= 0.5 * b.dims.x() && std::abs(l.y()) <= 0.5 * b.dims.y();
      }
      return n;
    };
    if (freeIn(*box) - freeIn(**other_reading) >= p.free_cells_to_swap) std::swap(*box, **other_reading);
  }
  return box;
}

}  // namespace slide::frontend
