#pragma once
// Line charts of values over time (e.g. ATE per pose), one line per series, with axes,
// a legend and each series' mean as a thin dashed line.
#include <string>
#include <vector>

#include "plot/canvas.h"

namespace slide::plot {

struct Series {
  std::string name;
  std::vector<double> x, y;
  Rgb colour{0, 90, 200};
  bool show_mean = true;
};

struct SeriesPlotOptions {
  std::string title, subtitle, x_label = "time [s]", y_label;
  int width = 1200, height = 520;
  bool y_from_zero = true;
};

// Throws std::invalid_argument when a series' x and y differ in length.
Canvas plotSeries(const std::vector<Series>& series, const SeriesPlotOptions& opts);

}  // namespace slide::plot
