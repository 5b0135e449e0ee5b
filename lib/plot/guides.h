#pragma once
// What helps a reader: axes with ticks and a grid, a metre scale bar, a legend, a title.
#include <string>
#include <vector>

#include "plot/canvas.h"
#include "plot/viewport.h"

namespace slide::plot {

// Frame around the viewport's area, ticks and labels on the left and bottom, a light grid.
void drawAxes(Canvas& c, const Viewport& vp, const std::string& x_label, const std::string& y_label);

// A bar of a round length (about a fifth of the width) at the area's bottom left, "10 m".
void drawScaleBar(Canvas& c, const Viewport& vp, const std::string& unit = "m");

struct LegendEntry {
  enum Kind { Patch, Line, Header } kind = Patch;
  std::string label;
  Style style;
};

// Width and height in pixels of the legend box for these entries.
Eigen::Vector2d legendSize(const std::vector<LegendEntry>& entries);
// Entries stacked downwards from (x, y), the top-left corner of the legend box.
void drawLegend(Canvas& c, double x, double y, const std::vector<LegendEntry>& entries);

// A vertical colour bar (rampColour) of the given size with its range and a label above.
void drawColourBar(Canvas& c, double x, double y, double w, double h, double lo, double hi, const std::string& label);

void drawTitle(Canvas& c, const std::string& title, const std::string& subtitle = "");

}  // namespace slide::plot
