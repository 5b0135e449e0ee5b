#include "plot/guides.h"

#include <algorithm>
#include <cmath>

#include "plot/palette.h"

namespace slide::plot {

namespace {
const Rgb kInk{40, 40, 40};
const Rgb kGrid{225, 225, 225};
constexpr double kLabelSize = 11;
}  // namespace

void drawAxes(Canvas& c, const Viewport& vp, const std::string& x_label, const std::string& y_label) {
  const PixelRect& a = vp.area();
  const auto& w = vp.world();
  const double sx = niceStep(w.sizes().x(), std::max(2, static_cast<int>(a.w / 90)));
  const double sy = niceStep(w.sizes().y(), std::max(2, static_cast<int>(a.h / 70)));
  Style grid;
  grid.stroke = kGrid;
  Style tick;
  tick.stroke = kInk;
  for (double x : ticks(w.min().x(), w.max().x(), sx)) {
    const double px = vp.toPixel({x, w.min().y()}).x();
    c.polyline({{px, a.y}, {px, a.y + a.h}}, grid);
    c.polyline({{px, a.y + a.h}, {px, a.y + a.h + 5}}, tick);
    c.text({px, a.y + a.h + 20}, tickLabel(x, sx), kLabelSize, kInk, TextAnchor::Middle);
  }
  for (double y : ticks(w.min().y(), w.max().y(), sy)) {
    const double py = vp.toPixel({w.min().x(), y}).y();
    c.polyline({{a.x, py}, {a.x + a.w, py}}, grid);
    c.polyline({{a.x - 5, py}, {a.x, py}}, tick);
    c.text({a.x - 8, py + kLabelSize / 2}, tickLabel(y, sy), kLabelSize, kInk, TextAnchor::End);
  }
  Style frame;
  frame.stroke = kInk;
  c.polygon({{a.x, a.y}, {a.x + a.w, a.y}, {a.x + a.w, a.y + a.h}, {a.x, a.y + a.h}}, frame);
  c.text({a.x + a.w / 2, a.y + a.h + 40}, x_label, 12, kInk, TextAnchor::Middle);
  c.text({std::max(6.0, a.x - 0.5 * Canvas::textWidth(y_label, 12)), a.y - 10}, y_label, 12, kInk);
}

void drawScaleBar(Canvas& c, const Viewport& vp, const std::string& unit) {
  const PixelRect& a = vp.area();
  const double len = niceStep(vp.world().sizes().x(), 5);
  const double px = len * vp.pixelsPerUnitX();
  const double x0 = a.x + 15, y0 = a.y + a.h - 15;
  Style bar;
  bar.stroke = kInk;
  bar.stroke_width = 3;
  c.polyline({{x0, y0}, {x0 + px, y0}}, bar);
  bar.stroke_width = 1.5;
  c.polyline({{x0, y0 - 6}, {x0, y0 + 2}}, bar);
  c.polyline({{x0 + px, y0 - 6}, {x0 + px, y0 + 2}}, bar);
  c.text({x0 + px / 2, y0 - 9}, tickLabel(len, len) + " " + unit, 12, kInk, TextAnchor::Middle);
}

constexpr double kRow = 20, kSize = 11;

Eigen::Vector2d legendSize(const std::vector<LegendEntry>& entries) {
  double width = 0;
  for (const auto& e : entries)
    width = std::max(width, Canvas::textWidth(e.label, kSize) + (e.kind == LegendEntry::Header ? 0 : 30));
  return {width + 18, entries.size() * kRow + 10};
}

void drawLegend(Canvas& c, double x, double y, const std::vector<LegendEntry>& entries) {
  if (entries.empty()) return;
  const Eigen::Vector2d size = legendSize(entries);
  const double w = size.x(), h = size.y();
  Style box;
  box.stroke = {190, 190, 190};
  box.filled = true;
  box.fill = {255, 255, 255};
  box.fill_opacity = 0.9;
  c.polygon({{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}}, box);
  double row = y + 5 + kRow / 2;
  for (const auto& e : entries) {
    const double sx = x + 8;
    if (e.kind == LegendEntry::Patch) {
      c.polygon({{sx, row - 6}, {sx + 22, row - 6}, {sx + 22, row + 6}, {sx, row + 6}}, e.style);
    } else if (e.kind == LegendEntry::Line) {
      c.polyline({{sx, row}, {sx + 22, row}}, e.style);
    }
    const double tx = e.kind == LegendEntry::Header ? sx : sx + 30;
    c.text({tx, row + kSize / 2}, e.label, kSize, kInk);
    row += kRow;
  }
}

void drawColourBar(Canvas& c, double x, double y, double w, double h, double lo, double hi, const std::string& label) {
  constexpr int kSteps = 48;
  for (int i = 0; i < kSteps; ++i) {
    const double y0 = y + h - (i + 1) * h / kSteps, y1 = y + h - i * h / kSteps;
    Style s;
    s.filled = true;
    s.fill = rampColour((i + 0.5) / kSteps);
    s.stroke_width = 0;
    c.polygon({{x, y0 - 0.5}, {x + w, y0 - 0.5}, {x + w, y1}, {x, y1}}, s);
  }
  Style frame;
  frame.stroke = kInk;
  c.polygon({{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}}, frame);
  const double step = niceStep(hi - lo, 5);
  for (double v : ticks(lo, hi, step)) {
    const double py = y + h - (hi > lo ? (v - lo) / (hi - lo) : 0) * h;
    c.polyline({{x + w, py}, {x + w + 4, py}}, frame);
    c.text({x + w + 7, py + 4}, tickLabel(v, step), 10, kInk);
  }
  c.text({x, y - 8}, label, 11, kInk);
}

void drawTitle(Canvas& c, const std::string& title, const std::string& subtitle) {
  c.text({20, 26}, title, 15, kInk);
  if (!subtitle.empty()) c.text({20, 46}, subtitle, 11, {100, 100, 100});
}

}  // namespace slide::plot
