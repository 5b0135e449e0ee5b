#pragma once
// Maps a rectangle of picture-plane coordinates (metres, v up) onto a pixel rectangle
// (y down), optionally with equal scale on both axes (maps), and picks round tick steps.
#include <Eigen/Geometry>
#include <vector>

namespace slide::plot {

struct PixelRect {
  double x = 0, y = 0, w = 0, h = 0;
};

class Viewport {
 public:
  // Grows `world` as needed so both axes share one scale when equal_aspect; an empty or
  // degenerate box becomes a 1 m square around its centre.
  Viewport(Eigen::AlignedBox2d world, PixelRect area, bool equal_aspect);

  Eigen::Vector2d toPixel(const Eigen::Vector2d& uv) const;
  double pixelsPerUnitX() const { return sx_; }
  double pixelsPerUnitY() const { return sy_; }
  const Eigen::AlignedBox2d& world() const { return world_; }
  const PixelRect& area() const { return area_; }

 private:
  Eigen::AlignedBox2d world_;
  PixelRect area_;
  double sx_ = 1, sy_ = 1;
};

// A round step (1, 2 or 5 times a power of ten) giving about `target` intervals over span.
double niceStep(double span, int target = 8);
// Multiples of step inside [lo, hi].
std::vector<double> ticks(double lo, double hi, double step);
// A tick label without needless digits ("0", "2.5", "-10", "0.05").
std::string tickLabel(double v, double step);

}  // namespace slide::plot
