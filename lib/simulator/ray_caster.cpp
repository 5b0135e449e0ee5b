#include "simulator/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "simulator/ray_shapes.h"

namespace slide::simulator {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

RayCaster::RayCaster(const World& world, double t, double cell_size) : terrain_(world.terrain), cell_(cell_size) {
  for (const io::GroundTruthObject& g : world.objects)
    add(g.at(t).model, g.semantic, static_cast<uint16_t>(g.object.id));
  for (const Structure& s : world.structures) add(s.model, s.semantic, 0);

  Eigen::AlignedBox2d all;
  for (const auto& b : boxes_) all.extend(b);
  if (prims_.empty()) return;
  grid_min_ = all.min();
  nx_ = std::max(1, static_cast<int>(std::ceil((all.max().x() - grid_min_.x()) / cell_)) + 1);
  ny_ = std::max(1, static_cast<int>(std::ceil((all.max().y() - grid_min_.y()) / cell_)) + 1);
  std::vector<uint32_t> counts(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  auto cellRange = [&](const Eigen::AlignedBox2d& b, int& x0, int& x1, int& y0, int& y1) {
    x0 = std::clamp(static_cast<int>((b.min().x() - grid_min_.x()) / cell_), 0, nx_ - 1);
    x1 = std::clamp(static_cast<int>((b.max().x() - grid_min_.x()) / cell_), 0, nx_ - 1);
    y0 = std::clamp(static_cast<int>((b.min().y() - grid_min_.y()) / cell_), 0, ny_ - 1);
    y1 = std::clamp(static_cast<int>((b.max().y() - grid_min_.y()) / cell_), 0, ny_ - 1);
  };
  for (const auto& b : boxes_) {
    int x0, x1, y0, y1;
    cellRange(b, x0, x1, y0, y1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) ++counts[static_cast<std::size_t>(y) * nx_ + x + 1];
  }
  for (std::size_t i = 1; i < counts.size(); ++i) counts[i] += counts[i - 1];
  cell_start_ = counts;
  cell_items_.resize(counts.back());
  std::vector<uint32_t> fill(counts.begin(), counts.end() - 1);
  for (uint32_t p = 0; p < boxes_.size(); ++p) {
    int x0, x1, y0, y1;
    cellRange(boxes_[p], x0, x1, y0, y1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        cell_items_[fill[static_cast<std::size_t>(y) * nx_ + x]++] = {
            p, static_cast<float>(prims_[p].zmin), static_cast<float>(prims_[p].zmax)};
  }
}

void RayCaster::add(const ObjectModel& m, uint16_t semantic, uint16_t instance) {
  Primitive p{};
  p.semantic = semantic;
  p.instance = instance;
  p.R.setIdentity();
  Eigen::AlignedBox3d box;
  if (const auto* c = std::get_if<Cylinder>(&m)) {
    p.kind = Kind::Cylinder;
    p.a = c->root;
    p.b = c->axis.normalized();
    p.c = {c->radius, c->length, 0};
    const Eigen::Vector3d top = c->root + c->length * p.b;
    box.extend(c->root);
    box.extend(top);
    box.min() -= Eigen::Vector3d::Constant(c->radius);
    box.max() += Eigen::Vector3d::Constant(c->radius);
  } else if (const auto* b = std::get_if<Cuboid>(&m)) {
    p.kind = Kind::Box;
    p.a = b->pose.translation();
    p.b = 0.5 * b->dims;
    p.R = b->pose.linear().transpose();
    const Eigen::Vector3d ext = b->pose.linear().cwiseAbs() * p.b;
    box.extend(p.a - ext);
    box.extend(p.a + ext);
  } else {
    const auto& e = std::get<Ellipsoid>(m);
    p.kind = Kind::Ellipsoid;
    p.a = e.centroid;
    p.b = {e.radius, e.radius, 0.5 * e.height};
    box.extend(p.a - p.b);
    box.extend(p.a + p.b);
  }
  p.zmin = box.min().z();
  p.zmax = box.max().z();
  scene_zmax_ = prims_.empty() ? p.zmax : std::max(scene_zmax_, p.zmax);
  prims_.push_back(p);
  boxes_.emplace_back(box.min().head<2>(), box.max().head<2>());
}

double RayCaster::intersect(const Primitive& p, const Eigen::Vector3d& o, const Eigen::Vector3d& d) const {
  switch (p.kind) {
    case Kind::Cylinder: return intersectRayCylinder(o, d, p.a, p.b, p.c.x(), p.c.y());
    case Kind::Box: return intersectRayBox(o, d, p.R, p.a, p.b);
    case Kind::Ellipsoid: return intersectRayEllipsoid(o, d, p.a, p.b);
  }
  return kInf;
}

bool RayCaster::cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range, RayHit* hit) const {
  double best = std::numeric_limits<double>::infinity();
  uint16_t best_sem = 0, best_inst = 0;
  // Flat ground and ceilings are cheap: intersect first and stop the grid walk there.
  uint16_t ground_label = 0;
  if (terrain_.flat()) {
    best = terrain_.intersect(o, d, max_range, &ground_label);
    best_sem = ground_label;
  } else {
    const double tc = terrain_.intersectCeiling(o, d, max_range);
    if (tc < best) best = tc, best_sem = terrain_.ceiling_semantic;
  }
  const double limit0 = std::min(best, max_range);
  // Uneven ground is checked cell by cell during the walk (ground_from: where to resume).
  const bool walk_ground = !terrain_.flat();
  const double ground_top = terrain_.maxHeight();
  double ground_from = 0;
  bool ground_done = !walk_ground;
  auto clearance = [&](double t) {  // height of the ray above the ground at t
    const Eigen::Vector3d p = o + t * d;
    return p.z() - terrain_.height(p.x(), p.y());
  };
  double g_from = walk_ground ? clearance(0) : 0;
  if (walk_ground && g_from <= 0) ground_done = true;  // starts below ground

  if (!prims_.empty()) {
    // Clip the ray's x-y projection to the grid rectangle.
    const Eigen::Vector2d gmax = grid_min_ + cell_ * Eigen::Vector2d(nx_, ny_);
    double t0 = 0, t1 = limit0;
    for (int i = 0; i < 2; ++i) {
      if (std::abs(d[i]) < 1e-12) {
        if (o[i] < grid_min_[i] || o[i] > gmax[i]) t1 = -1;
        continue;
      }
      double a = (grid_min_[i] - o[i]) / d[i], b = (gmax[i] - o[i]) / d[i];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    if (t0 <= t1 && t0 > 0 && !ground_done) {  // ground between the origin and the grid
      const double tg = terrain_.intersect(o, d, std::min(t0, limit0), &ground_label);
      if (tg < best) best = tg, best_sem = ground_label, best_inst = 0, ground_done = true;
      ground_from = t0;
      if (!ground_done) g_from = clearance(t0);
    }
    if (t0 <= t1 && t0 < best) {
      const Eigen::Vector2d p0 = o.head<2>() + t0 * d.head<2>();
      int ix = std::clamp(static_cast<int>((p0.x() - grid_min_.x()) / cell_), 0, nx_ - 1);
      int iy = std::clamp(static_cast<int>((p0.y() - grid_min_.y()) / cell_), 0, ny_ - 1);
      const int sx = d.x() > 0 ? 1 : -1, sy = d.y() > 0 ? 1 : -1;
      auto nextBoundary = [&](int i, int idx, int s) {
        if (std::abs(d[i]) < 1e-12) return kInf;
        const double edge = grid_min_[i] + cell_ * (idx + (s > 0 ? 1 : 0));
        return (edge - o[i]) / d[i];
      };
      double tx = nextBoundary(0, ix, sx), ty = nextBoundary(1, iy, sy);
      const double dtx = std::abs(d.x()) < 1e-12 ? kInf : cell_ / std::abs(d.x());
      const double dty = std::abs(d.y()) < 1e-12 ? kInf : cell_ / std::abs(d.y());
      double t_enter = t0;
      uint32_t recent[8];
      std::fill(std::begin(recent), std::end(recent), UINT32_MAX);
      uint32_t recent_next = 0;
      while (true) {
        const double t_exit = std::min({tx, ty, t1});
        const double z0 = o.z() + t_enter * d.z(), z1 = o.z() + t_exit * d.z();
        const double zlo = std::min(z0, z1), zhi = std::max(z0, z1);
        if (d.z() > 0 && zlo > scene_zmax_) break;
        const std::size_t cell = static_cast<std::size_t>(iy) * nx_ + ix;
        for (uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
          const CellItem& item = cell_items_[k];
          if (zhi < item.zmin || zlo > item.zmax) continue;
          // Shapes spanning several cells: skip those this ray tested recently.
          bool seen = false;
          for (uint32_t m : recent) seen = seen || m == item.prim;
          if (seen) continue;
          recent[recent_next++ & 7u] = item.prim;
          const Primitive& p = prims_[item.prim];
          const double t = intersect(p, o, d);
          if (t < best) best = t, best_sem = p.semantic, best_inst = p.instance;
        }
        if (!ground_done) {
          if (d.z() >= 0 && zlo > ground_top) {
            ground_done = true;  // above every hill and not coming down
          } else if (const double g_exit = clearance(t_exit); g_exit <= 0) {
            // The ground crossing lies in this cell: refine by false position (smooth ground).
            double lo = ground_from, hi = t_exit, glo = g_from, ghi = g_exit, tg = hi;
            for (int i = 0; i < 3 && hi - lo > 1e-3; ++i) {
              tg = lo + (hi - lo) * glo / (glo - ghi);
              const double gm = clearance(tg);
              if (std::abs(gm) < 1e-3) break;
              if (gm > 0) lo = tg, glo = gm;
              else hi = tg, ghi = gm;
            }
            if (tg < best) best = tg, best_sem = terrain_.semantic, best_inst = 0;
            ground_done = true;
          } else {
            ground_from = t_exit;
            g_from = g_exit;
          }
        }
        if (best <= t_exit || t_exit >= t1) break;
        t_enter = t_exit;
        if (tx < ty) {
          ix += sx;
          tx += dtx;
        } else {
          iy += sy;
          ty += dty;
        }
        if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_) break;
      }
    }
  }
  // Ground beyond the walked cells (only in front of the nearest object).
  if (!ground_done && ground_from < std::min(best, max_range)) {
    const double tg = terrain_.intersect(o, d, std::min(best, max_range), &ground_label, ground_from);
    if (tg < best) best = tg, best_sem = ground_label, best_inst = 0;
  }
  if (!(best < max_range)) return false;
  hit->range = best;
  hit->semantic = best_sem;
  hit->instance = best_inst;
  return true;
}

namespace {
// Azimuth span [lo, hi] (hi - lo < 2 pi) of points seen from the origin, around `centre`.
void angularSpan(const std::vector<Eigen::Vector2d>& pts, const Eigen::Vector2d& o, double& lo, double& hi) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  const double a0 = std::atan2(mean.y() - o.y(), mean.x() - o.x());
  lo = hi = a0;
  for (const auto& p : pts) {
    const double a = a0 + wrapAngle(std::atan2(p.y() - o.y(), p.x() - o.x()) - a0);
    lo = std::min(lo, a);
    hi = std::max(hi, a);
  }
}
}  // namespace

OriginView::OriginView(const RayCaster& caster, const Eigen::Vector3d& origin, double max_range, int bins)
    : caster_(caster), origin_(origin), bins_(bins) {
  const Eigen::Vector2d o = origin.head<2>();
  struct Span {
    uint32_t prim;
    int b0, nb;  // first bin and number of bins
    float dmin, dmax;
  };
  std::vector<Span> spans;
  const double to_bin = bins / (2 * M_PI);
  for (uint32_t i = 0; i < caster.prims_.size(); ++i) {
    const auto& p = caster.prims_[i];
    double dmin, dmax, lo = 0, hi = 0;
    bool all = false;
    if (p.kind == RayCaster::Kind::Box) {
      // Footprint corners of the oriented box (its x-y projection).
      const Eigen::Matrix3d Rt = p.R.transpose();  // box to world
      std::vector<Eigen::Vector2d> corners;
      for (int k = 0; k < 8; ++k) {
        const Eigen::Vector3d c(k & 1 ? p.b.x() : -p.b.x(), k & 2 ? p.b.y() : -p.b.y(), k & 4 ? p.b.z() : -p.b.z());
        corners.push_back((p.a + Rt * c).head<2>());
      }
      const Eigen::Vector3d ol = p.R * (origin - p.a);
      const Eigen::Vector3d q = ol.cwiseMax(-p.b).cwiseMin(p.b);
      dmin = std::hypot(ol.x() - q.x(), ol.y() - q.y());
      dmax = 0;
      for (const auto& c : corners) dmax = std::max(dmax, (c - o).norm());
      if (std::abs(ol.x()) <= p.b.x() && std::abs(ol.y()) <= p.b.y()) all = true;
      else angularSpan(corners, o, lo, hi);
    } else {
      const Eigen::AlignedBox2d& box = caster.boxes_[i];
      const Eigen::Vector2d c = box.center();
      const double r = 0.5 * box.sizes().norm();
      const double d = (c - o).norm();
      dmin = std::max(0.0, d - r);
      dmax = d + r;
      if (d <= r * 1.0001) {
        all = true;
      } else {
        const double a = std::atan2(c.y() - o.y(), c.x() - o.x()), half = std::asin(r / d);
        lo = a - half, hi = a + half;
      }
    }
    if (dmin > max_range) continue;
    Span s{i, 0, bins, static_cast<float>(dmin), static_cast<float>(dmax)};
    if (!all && hi - lo < 2 * M_PI) {
      s.b0 = static_cast<int>(std::floor((lo + M_PI) * to_bin));
      s.nb = std::min(bins, static_cast<int>(std::floor((hi + M_PI) * to_bin)) - s.b0 + 1);
    }
    spans.push_back(s);
  }
  start_.assign(static_cast<std::size_t>(bins) + 1, 0);
  auto wrap = [bins](int b) { return ((b % bins) + bins) % bins; };
  for (const Span& s : spans)
    for (int k = 0; k < s.nb; ++k) ++start_[wrap(s.b0 + k) + 1];
  for (int b = 0; b < bins; ++b) start_[b + 1] += start_[b];
  entries_.resize(start_.back());
  std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
  for (const Span& s : spans) {
    const auto& p = caster.prims_[s.prim];
    const Entry e{s.prim, s.dmin, s.dmax, static_cast<float>(p.zmin), static_cast<float>(p.zmax)};
    for (int k = 0; k < s.nb; ++k) entries_[fill[wrap(s.b0 + k)]++] = e;
  }
  for (int b = 0; b < bins; ++b)
    std::sort(entries_.begin() + start_[b], entries_.begin() + start_[b + 1],
              [](const Entry& x, const Entry& y) { return x.dmin < y.dmin; });

  const Terrain& terrain = caster.terrain_;
  if (!terrain.flat()) {
    ground_bins_ = 720;
    for (double r = 0.2; r < max_range + 1; r += std::max(0.25, 0.03 * r)) radii_.push_back(r);
    const std::size_t n = radii_.size();
    ground_slope_max_.resize(static_cast<std::size_t>(ground_bins_) * n);
    for (int b = 0; b < ground_bins_; ++b) {
      const double a = (b + 0.5) * 2 * M_PI / ground_bins_ - M_PI;
      const double ca = std::cos(a), sa = std::sin(a);
      float run = -std::numeric_limits<float>::infinity();
      for (std::size_t j = 0; j < n; ++j) {
        const double r = radii_[j];
        const double e = (terrain.height(origin.x() + r * ca, origin.y() + r * sa) - origin.z()) / r;
        run = std::max(run, static_cast<float>(e));
        ground_slope_max_[static_cast<std::size_t>(b) * n + j] = run;
      }
    }
  }
}

double OriginView::groundHit(const Eigen::Vector3d& d, double h, double slope, double max_range, int gbin) const {
  const Terrain& terrain = caster_.terrain_;
  const Eigen::Vector3d& o = origin_;
  const std::size_t n = radii_.size();
  const float* row = &ground_slope_max_[static_cast<std::size_t>(gbin) * n];
  // Slopes are compared with a small margin: the ray's azimuth is not exactly the bin's.
  const float m = static_cast<float>(slope) - 0.01f;
  const std::size_t j = static_cast<std::size_t>(std::lower_bound(row, row + n, m) - row);
  if (j >= n) return std::numeric_limits<double>::infinity();
  const double t_start = j > 0 ? radii_[j - 1] / h : 0.0;
  if (t_start >= max_range) return std::numeric_limits<double>::infinity();
  // Usually the crossing lies between the two table radii: false position there.
  auto clearance = [&](double t) {
    const Eigen::Vector3d p = o + t * d;
    return p.z() - terrain.height(p.x(), p.y());
  };
  double lo = t_start, hi = radii_[j] / h;
  double glo = clearance(lo), ghi = clearance(hi);
  if (glo > 0 && ghi <= 0) {
    double t = hi;
    for (int i = 0; i < 6 && hi - lo > 1e-3; ++i) {
      t = lo + (hi - lo) * glo / (glo - ghi);
      const double g = clearance(t);
      if (std::abs(g) < 1e-3) break;
      if (g > 0) lo = t, glo = g;
      else hi = t, ghi = g;
    }
    return t < max_range ? t : std::numeric_limits<double>::infinity();
  }
  uint16_t label = 0;
  return terrain.intersect(o, d, max_range, &label, t_start);
}

bool OriginView::cast(const Eigen::Vector3d& d, double max_range, RayHit* hit) const {
  const Eigen::Vector3d& o = origin_;
  const double h = std::sqrt(d.x() * d.x() + d.y() * d.y());
  if (h < 1e-6) return caster_.cast(o, d, max_range, hit);
  const Terrain& terrain = caster_.terrain_;
  double best = std::numeric_limits<double>::infinity();
  uint16_t best_sem = 0, best_inst = 0, ground_label = 0;
  if (terrain.flat()) {
    best = terrain.intersect(o, d, max_range, &ground_label);
    best_sem = ground_label;
  } else {
    const double tc = terrain.intersectCeiling(o, d, max_range);
    if (tc < best) best = tc, best_sem = terrain.ceiling_semantic;
  }
  const double azimuth01 = (std::atan2(d.y(), d.x()) + M_PI) / (2 * M_PI);
  const int bin = std::min(bins_ - 1, static_cast<int>(azimuth01 * bins_));
  const double slope = d.z() / h;  // rise per horizontal metre
  const double limit = std::min(best, max_range);
  for (uint32_t k = start_[bin]; k < start_[bin + 1]; ++k) {
    const Entry& e = entries_[k];
    if (e.dmin >= std::min(best, limit) * h) break;  // everything further starts beyond the best hit
    const double z0 = o.z() + e.dmin * slope, z1 = o.z() + e.dmax * slope;
    if (slope > 0 && z0 > caster_.scene_zmax_) break;  // climbing above every shape
    if (std::max(z0, z1) < e.zmin || std::min(z0, z1) > e.zmax) continue;
    const double t = caster_.intersect(caster_.prims_[e.prim], o, d);
    if (t < best) best = t, best_sem = caster_.prims_[e.prim].semantic, best_inst = caster_.prims_[e.prim].instance;
  }
  if (!terrain.flat()) {
    const int gbin = std::min(ground_bins_ - 1, static_cast<int>(azimuth01 * ground_bins_));
    const double tg = groundHit(d, h, slope, std::min(best, max_range), gbin);
    if (tg < best) best = tg, best_sem = terrain.semantic, best_inst = 0;
  }
  if (!(best < max_range)) return false;
  hit->range = best;
  hit->semantic = best_sem;
  hit->instance = best_inst;
  return true;
}

}  // namespace slide::simulator
