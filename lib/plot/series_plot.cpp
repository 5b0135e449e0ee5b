#include "plot/series_plot.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "plot/guides.h"
#include "plot/viewport.h"

namespace slide::plot {

Canvas plotSeries(const std::vector<Series>& series, const SeriesPlotOptions& opts) {
  Eigen::AlignedBox2d frame;
  for (const Series& s : series) {
    if (s.x.size() != s.y.size()) throw std::invalid_argument("series '" + s.name + "': x and y differ in length");
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) frame.extend(Eigen::Vector2d(s.x[i], s.y[i]));
  }
  if (frame.isEmpty()) frame = Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1));
  if (opts.y_from_zero) frame.extend(Eigen::Vector2d(frame.min().x(), 0.0));
  frame.extend(Eigen::Vector2d(frame.max().x(), frame.max().y() + 0.05 * std::max(frame.sizes().y(), 1e-6)));

  constexpr double kLegendWidth = 230;
  Canvas c(opts.width, opts.height);
  const PixelRect area{80, 80, opts.width - 80 - kLegendWidth - 20.0, opts.height - 80 - 65.0};
  const Viewport vp(frame, area, false);
  drawAxes(c, vp, opts.x_label, opts.y_label);

  std::vector<LegendEntry> legend;
  for (const Series& s : series) {
    std::vector<Eigen::Vector2d> px;
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      px.push_back(vp.toPixel({s.x[i], s.y[i]}));
      sum += s.y[i];
      ++n;
    }
    Style line;
    line.stroke = s.colour;
    line.stroke_width = 1.8;
    c.polyline(px, line);
    std::ostringstream label;
    label.precision(3);
    label << s.name;
    if (s.show_mean && n) {
      const double m = sum / n;
      Style dash = line;
      dash.stroke_width = 1.0;
      dash.dashed = true;
      const double py = vp.toPixel({0, m}).y();
      c.polyline({{area.x, py}, {area.x + area.w, py}}, dash);
      label << " (mean " << m << ")";
    }
    legend.push_back({LegendEntry::Line, label.str(), line});
  }
  drawLegend(c, std::min(opts.width - kLegendWidth - 10, opts.width - legendSize(legend).x() - 8), area.y, legend);
  drawTitle(c, opts.title, opts.subtitle);
  return c;
}

}  // namespace slide::plot
