#include "sim/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/ray_shapes.h"

namespace slide {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

RayCaster::RayCaster(const World& world, double t, double cell_size) : terrain_(world.terrain), cell_(cell_size) {
  for (const GroundTruthObject& g : world.objects)
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

}  // namespace slide
