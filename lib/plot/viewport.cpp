#include "plot/viewport.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace slide::plot {

Viewport::Viewport(Eigen::AlignedBox2d world, PixelRect area, bool equal_aspect) : area_(area) {
  if (world.isEmpty()) world = Eigen::AlignedBox2d(Eigen::Vector2d(-0.5, -0.5), Eigen::Vector2d(0.5, 0.5));
  Eigen::Vector2d size = world.sizes();
  const Eigen::Vector2d c = world.center();
  for (int i = 0; i < 2; ++i)
    if (size[i] < 1e-9) size[i] = 1.0;
  sx_ = area.w / size.x();
  sy_ = area.h / size.y();
  if (equal_aspect) {
    sx_ = sy_ = std::min(sx_, sy_);
    size = Eigen::Vector2d(area.w / sx_, area.h / sy_);
  }
  world_ = Eigen::AlignedBox2d(c - size / 2, c + size / 2);
}

Eigen::Vector2d Viewport::toPixel(const Eigen::Vector2d& uv) const {
  return {area_.x + (uv.x() - world_.min().x()) * sx_, area_.y + area_.h - (uv.y() - world_.min().y()) * sy_};
}

double niceStep(double span, int target) {
  if (!(span > 0) || !std::isfinite(span)) return 1.0;
  const double raw = span / std::max(1, target);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

std::vector<double> ticks(double lo, double hi, double step) {
  std::vector<double> out;
  if (!(step > 0)) return out;
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step && out.size() < 1000; k += 1)
    out.push_back(std::abs(k * step) < 1e-12 * step ? 0.0 : k * step);
  return out;
}

std::string tickLabel(double v, double step) {
  const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << v;
  return s.str();
}

}  // namespace slide::plot
