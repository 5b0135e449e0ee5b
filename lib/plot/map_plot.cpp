#include "plot/map_plot.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include "plot/guides.h"
#include "plot/object_shapes.h"
#include "plot/palette.h"
#include "plot/viewport.h"

namespace slide::plot {

namespace {
constexpr double kLegendWidth = 250;
const Rgb kTruth{20, 20, 20};

Rgb classColour(const ClassTable& classes, int class_id) {
  const ClassInfo* c = classes.find(class_id);
  if (!c) return {128, 128, 128};
  return {c->color.x(), c->color.y(), c->color.z()};
}

std::string className(const ClassTable& classes, int class_id) {
  const ClassInfo* c = classes.find(class_id);
  return c ? c->name : "class " + std::to_string(class_id);
}

std::vector<Eigen::Vector2d> toPixels(const Viewport& vp, const std::vector<Eigen::Vector2d>& uv) {
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : uv) out.push_back(vp.toPixel(p));
  return out;
}

double pathLength(const std::vector<Eigen::Vector3d>& p) {
  double l = 0;
  for (std::size_t i = 1; i < p.size(); ++i) l += (p[i] - p[i - 1]).norm();
  return l;
}

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

struct Grid {
  double step, z, x0, x1, y0, y1;
};

// A ground grid of round step on the plane z = lowest point, covering the x-y box.
Grid groundGrid(const Eigen::AlignedBox3d& box) {
  Grid g;
  g.step = niceStep(std::max(box.sizes().x(), box.sizes().y()), 10);
  g.z = box.min().z();
  g.x0 = std::floor(box.min().x() / g.step) * g.step;
  g.x1 = std::ceil(box.max().x() / g.step) * g.step;
  g.y0 = std::floor(box.min().y() / g.step) * g.step;
  g.y1 = std::ceil(box.max().y() / g.step) * g.step;
  return g;
}

// The part of segment a-b inside the rectangle (Liang-Barsky); false when none is.
bool clipSegment(Eigen::Vector2d& a, Eigen::Vector2d& b, const PixelRect& r) {
  const Eigen::Vector2d d = b - a;
  double t0 = 0, t1 = 1;
  const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
  const double q[4] = {a.x() - r.x, r.x + r.w - a.x(), a.y() - r.y, r.y + r.h - a.y()};
  for (int i = 0; i < 4; ++i) {
    if (std::abs(p[i]) < 1e-12) {
      if (q[i] < 0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
  }
  if (t0 > t1) return false;
  const Eigen::Vector2d a0 = a;
  a = a0 + t0 * d;
  b = a0 + t1 * d;
  return true;
}

void drawGroundGrid(Canvas& c, const Viewport& vp, const View& view, const Grid& g) {
  const double step = g.step, z = g.z, x0 = g.x0, x1 = g.x1, y0 = g.y0, y1 = g.y1;
  Style grid;
  grid.stroke = {215, 215, 215};
  auto line = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
    Eigen::Vector2d a = vp.toPixel(view.project(p)), b = vp.toPixel(view.project(q));
    if (clipSegment(a, b, vp.area())) c.polyline({a, b}, grid);
  };
  // Extend the grid well beyond the objects; clipping keeps it inside the picture.
  const double span = std::max(x1 - x0, y1 - y0);
  for (double x : ticks(x0 - span, x1 + span, step)) line({x, y0 - span, z}, {x, y1 + span, z});
  for (double y : ticks(y0 - span, y1 + span, step)) line({x0 - span, y, z}, {x1 + span, y, z});
  c.text({vp.area().x + vp.area().w - 10, vp.area().y + vp.area().h - 12}, "grid " + tickLabel(step, step) + " m", 10,
         {120, 120, 120}, TextAnchor::End);
}

// Arrows showing where world x and y point in an oblique picture.
void drawCompass(Canvas& c, const Viewport& vp, const View& view) {
  const Eigen::Vector2d o(vp.area().x + vp.area().w - 60, vp.area().y + 60);
  const Rgb ink{60, 60, 60};
  for (auto [axis, label] : {std::pair{Eigen::Vector3d::UnitX().eval(), "x"}, {Eigen::Vector3d::UnitY().eval(), "y"},
                             {Eigen::Vector3d::UnitZ().eval(), "z"}}) {
    Eigen::Vector2d d = view.project(axis);
    d.y() = -d.y();  // picture v up -> pixels down
    if (d.norm() < 0.05) continue;
    const Eigen::Vector2d tip = o + 35 * d;
    Style s;
    s.stroke = ink;
    s.stroke_width = 1.5;
    c.polyline({o, tip}, s);
    c.text(tip + 8 * d.normalized() + Eigen::Vector2d(-3, 4), label, 11, ink);
  }
}
}  // namespace

Canvas plotMap(const std::vector<PlotMap>& maps, const std::vector<PlotTrajectory>& trajectories,
               const ClassTable& classes, const MapPlotOptions& opts) {
  const View& view = opts.view;
  // Project everything first to frame the picture.
  std::vector<std::vector<ObjectFacets>> facets(maps.size());
  Eigen::AlignedBox2d frame;
  Eigen::AlignedBox3d box3;
  for (std::size_t m = 0; m < maps.size(); ++m)
    for (const Object& o : maps[m].objects) {
      facets[m].push_back(objectFacets(o, view));
      for (const auto& p : facets[m].back().silhouette) frame.extend(p);
      box3.extend(o.position() - 0.5 * o.extent());
      box3.extend(o.position() + 0.5 * o.extent());
    }
  std::vector<std::vector<Eigen::Vector2d>> paths;
  for (const auto& t : trajectories) {
    paths.emplace_back();
    for (const auto& p : t.positions) {
      paths.back().push_back(view.project(p));
      frame.extend(paths.back().back());
      box3.extend(p);
    }
  }
  double point_z0 = 0, point_z1 = 1;
  if (!opts.points.empty()) {
    std::vector<double> zs;
    for (const auto& p : opts.points) {
      frame.extend(view.project(p));
      zs.push_back(p.z());
    }
    std::sort(zs.begin(), zs.end());
    point_z0 = zs[zs.size() / 50], point_z1 = std::max(point_z0 + 0.1, zs[zs.size() * 49 / 50]);
  }
  std::optional<Grid> grid;
  if (!view.isTop() && !box3.isEmpty()) {
    grid = groundGrid(box3);
  }
  if (!frame.isEmpty()) {
    const Eigen::Vector2d pad = (0.04 * frame.sizes()).cwiseMax(Eigen::Vector2d::Constant(1.0));
    frame.extend(frame.min() - pad);
    frame.extend(frame.max() + pad);
  }

  Canvas c(opts.width, opts.height);
  const PixelRect area{75, 70, opts.width - 75 - kLegendWidth - 20.0, opts.height - 70 - 65.0};
  const Viewport vp(frame, area, true);
  if (view.isTop()) {
    drawAxes(c, vp, "x [m]", "y [m]");
  } else if (grid) {
    drawGroundGrid(c, vp, view, *grid);
    // Shadows: each object's footprint on the ground, so heights read at a glance.
    Style shadow;
    shadow.filled = true;
    shadow.fill = {200, 200, 200};
    shadow.fill_opacity = 0.6;
    shadow.stroke_width = 0;
    for (const auto& m : maps)
      for (const Object& o : m.objects) {
        if (m.ground_truth) continue;
        std::vector<Eigen::Vector2d> px;
        for (const auto& p : objectFacets(o, View::top()).silhouette)
          px.push_back(vp.toPixel(view.project({p.x(), p.y(), grid->z})));
        c.polygon(px, shadow);
      }
  }

  if (!opts.points.empty()) {
    std::vector<char> used(static_cast<std::size_t>(opts.width) * opts.height, 0);
    Style dot;
    dot.stroke_width = 0;
    dot.filled = true;
    for (const auto& p : opts.points) {
      const Eigen::Vector2d px = vp.toPixel(view.project(p));
      const int x = static_cast<int>(px.x()), y = static_cast<int>(px.y());
      if (x < 0 || y < 0 || x >= opts.width || y >= opts.height || used[static_cast<std::size_t>(y) * opts.width + x]) continue;
      used[static_cast<std::size_t>(y) * opts.width + x] = 1;
      const double t = std::clamp((p.z() - point_z0) / (point_z1 - point_z0), 0.0, 1.0);
      const int g = static_cast<int>(200 - 160 * t);
      dot.fill = {g, g, g};
      c.circle(px, 0.7, dot);
    }
  }

  // Objects, far first; estimated maps filled, ground truth outlined on top.
  std::vector<std::tuple<double, std::size_t, std::size_t>> order;
  for (std::size_t m = 0; m < maps.size(); ++m)
    for (std::size_t i = 0; i < facets[m].size(); ++i) order.emplace_back(-facets[m][i].depth, m, i);
  std::sort(order.begin(), order.end());
  std::size_t est_maps = 0;
  for (const auto& m : maps) est_maps += !m.ground_truth;
  for (bool truth : {false, true})
    for (const auto& [neg_depth, m, i] : order) {
      if (maps[m].ground_truth != truth) continue;
      const Object& o = maps[m].objects[i];
      const Rgb colour = classColour(classes, o.class_id);
      if (truth) {
        Style s;
        s.stroke = kTruth;
        s.stroke_width = 1.3;
        s.dashed = true;
        const auto px = toPixels(vp, facets[m][i].silhouette);
        Eigen::AlignedBox2d px_box;
        for (const auto& p : px) px_box.extend(p);
        if (px_box.isEmpty() || px_box.sizes().maxCoeff() < 8) {
          s.dashed = false;
          c.circle(vp.toPixel(view.project(o.position())), 5, s);  // small truth: a ring
        } else {
          c.polygon(px, s);
        }
        continue;
      }
      // Objects too small to see at this scale become a dot of their class colour.
      Eigen::AlignedBox2d px_box;
      for (const auto& p : toPixels(vp, facets[m][i].silhouette)) px_box.extend(p);
      if (px_box.isEmpty() || px_box.sizes().maxCoeff() < 6) {
        Style dot;
        dot.filled = true;
        dot.fill = colour;
        dot.stroke = est_maps > 1 ? robotColour(maps[m].robot) : shadeColour(colour, 0.55);
        c.circle(vp.toPixel(view.project(o.position())), 3.5, dot);
        continue;
      }
      for (const Facet& f : facets[m][i].facets) {
        Style s;
        s.filled = true;
        s.fill = shadeColour(colour, f.shade);
        s.fill_opacity = opts.fill_opacity;
        s.stroke = est_maps > 1 ? robotColour(maps[m].robot) : shadeColour(colour, 0.55);
        s.stroke_width = est_maps > 1 ? 1.6 : 1.0;
        c.polygon(toPixels(vp, f.uv), s);
      }
      if (opts.label_ids && o.id >= 0) {
        const Eigen::Vector2d p = vp.toPixel(view.project(o.position()));
        c.text(p + Eigen::Vector2d(6, -6), std::to_string(o.id), 9, {60, 60, 60});
      }
    }

  // Range of the values that colour trajectories, if any.
  std::optional<std::pair<double, double>> value_range;
  for (std::size_t t = 0; t < trajectories.size(); ++t)
    if (trajectories[t].values.size() == trajectories[t].positions.size())
      for (double v : trajectories[t].values) {
        if (!std::isfinite(v)) continue;
        if (!value_range) value_range = std::make_pair(v, v);
        value_range->first = std::min(value_range->first, v);
        value_range->second = std::max(value_range->second, v);
      }

  // Trajectories: ground truth first (dashed black), estimates on top.
  for (bool truth : {true, false})
    for (std::size_t t = 0; t < trajectories.size(); ++t) {
      if (trajectories[t].ground_truth != truth || paths[t].empty()) continue;
      Style s;
      s.stroke = truth ? kTruth : robotColour(trajectories[t].robot);
      s.stroke_width = truth ? 1.5 : 2.4;
      s.dashed = truth;
      const auto px = toPixels(vp, paths[t]);
      const auto& values = trajectories[t].values;
      if (!truth && values.size() == px.size() && value_range) {
        // Coloured by value: one short segment per pose pair.
        for (std::size_t i = 1; i < px.size(); ++i) {
          Style seg = s;
          seg.stroke = rampColour((0.5 * (values[i - 1] + values[i]) - value_range->first) /
                                  std::max(1e-12, value_range->second - value_range->first));
          seg.stroke_width = 3.0;
          c.polyline({px[i - 1], px[i]}, seg);
        }
      } else {
        c.polyline(px, s);
      }
      if (truth) continue;
      Style start;
      start.filled = true;
      start.fill = s.stroke;
      start.stroke = {255, 255, 255};
      start.stroke_width = 1.5;
      c.circle(px.front(), 6, start);
      const Eigen::Vector2d e = px.back();
      c.polygon({e + Eigen::Vector2d(-5, -5), e + Eigen::Vector2d(5, -5), e + Eigen::Vector2d(5, 5), e + Eigen::Vector2d(-5, 5)},
                start);
    }

  // Scoring overlay: matches, false positives, missed truth.
  const MatchOverlay& ov = opts.overlay;
  Style match_style;
  match_style.stroke = {0, 150, 60};
  match_style.stroke_width = 2;
  Style wrong_style;
  wrong_style.stroke = {230, 0, 0};
  wrong_style.stroke_width = 2;
  for (const auto& [e, g] : ov.matches) c.polyline({vp.toPixel(view.project(e)), vp.toPixel(view.project(g))}, match_style);
  for (const auto& p : ov.false_positives) {
    const Eigen::Vector2d q = vp.toPixel(view.project(p));
    c.polyline({q + Eigen::Vector2d(-6, -6), q + Eigen::Vector2d(6, 6)}, wrong_style);
    c.polyline({q + Eigen::Vector2d(-6, 6), q + Eigen::Vector2d(6, -6)}, wrong_style);
  }
  for (const auto& p : ov.missed) c.circle(vp.toPixel(view.project(p)), 8, wrong_style);

  if (!view.isTop()) {
    drawScaleBar(c, vp);
    drawCompass(c, vp, view);
  }

  // Legend: classes present, robots, ground truth, markers.
  std::vector<LegendEntry> legend;
  std::map<int, int> class_counts;
  for (const auto& m : maps)
    if (!m.ground_truth)
      for (const Object& o : m.objects) class_counts[o.class_id]++;
  if (!class_counts.empty()) legend.push_back({LegendEntry::Header, "classes (objects)", {}});
  for (const auto& [id, n] : class_counts) {
    Style s;
    s.filled = true;
    s.fill = classColour(classes, id);
    s.fill_opacity = opts.fill_opacity;
    s.stroke = shadeColour(s.fill, 0.55);
    legend.push_back({LegendEntry::Patch, className(classes, id) + " (" + std::to_string(n) + ")", s});
  }
  bool any_robot = false;
  for (std::size_t t = 0; t < trajectories.size(); ++t) {
    if (trajectories[t].ground_truth) continue;
    if (!any_robot) legend.push_back({LegendEntry::Header, "trajectories", {}});
    any_robot = true;
    Style s;
    const bool by_value = value_range && trajectories[t].values.size() == trajectories[t].positions.size();
    s.stroke = by_value ? rampColour(0.5) : robotColour(trajectories[t].robot);
    s.stroke_width = 2.4;
    legend.push_back({LegendEntry::Line,
                      trajectories[t].name + " (" + fixed(pathLength(trajectories[t].positions), 0) + " m)", s});
  }
  if (est_maps > 1) {
    legend.push_back({LegendEntry::Header, "maps (outline)", {}});
    for (const auto& m : maps) {
      if (m.ground_truth) continue;
      Style s;
      s.stroke = robotColour(m.robot);
      s.stroke_width = 1.6;
      legend.push_back({LegendEntry::Patch, m.name + " (" + std::to_string(m.objects.size()) + ")", s});
    }
  }
  std::size_t gt_objects = 0;
  bool gt_traj = false;
  for (const auto& m : maps)
    if (m.ground_truth) gt_objects += m.objects.size();
  for (const auto& t : trajectories) gt_traj |= t.ground_truth;
  if (gt_objects || gt_traj) legend.push_back({LegendEntry::Header, "ground truth", {}});
  Style truth_style;
  truth_style.stroke = kTruth;
  truth_style.stroke_width = 1.4;
  truth_style.dashed = true;
  if (gt_objects) legend.push_back({LegendEntry::Patch, "objects (" + std::to_string(gt_objects) + ")", truth_style});
  if (gt_traj) legend.push_back({LegendEntry::Line, "trajectory", truth_style});
  if (!ov.matches.empty() || !ov.false_positives.empty() || !ov.missed.empty()) {
    legend.push_back({LegendEntry::Header, "scoring", {}});
    legend.push_back({LegendEntry::Line, "match (" + std::to_string(ov.matches.size()) + ")", match_style});
    legend.push_back({LegendEntry::Line, "x false positive (" + std::to_string(ov.false_positives.size()) + ")", wrong_style});
    Style ring = wrong_style;
    legend.push_back({LegendEntry::Patch, "o missed (" + std::to_string(ov.missed.size()) + ")", ring});
  }
  if (any_robot) legend.push_back({LegendEntry::Header, "circle: start, square: end", {}});
  const double legend_x = std::min(opts.width - kLegendWidth - 10, opts.width - legendSize(legend).x() - 8);
  drawLegend(c, legend_x, area.y, legend);
  if (value_range)
    drawColourBar(c, legend_x + 10, area.y + legendSize(legend).y() + 40, 22, std::min(260.0, area.h / 2),
                  value_range->first, value_range->second, opts.values_label);

  std::string subtitle = opts.subtitle;
  if (subtitle.empty()) {
    subtitle = view.isTop() ? "top view" : "oblique view (azimuth " + fixed(view.azimuth_deg, 0) + " deg, elevation " +
                                               fixed(view.elevation_deg, 0) + " deg)";
  }
  drawTitle(c, opts.title, subtitle);
  return c;
}

}  // namespace slide::plot
