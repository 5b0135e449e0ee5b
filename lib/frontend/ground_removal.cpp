#include "frontend/ground_removal.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slide::frontend {

namespace {
// Minimum filter of radius w along rows then columns (separable for a square window).
std::vector<float> minFilter(const std::vector<float>& g, int nx, int ny, int w) {
  std::vector<float> tmp(g.size()), out(g.size());
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      float m = std::numeric_limits<float>::infinity();
      for (int k = std::max(0, x - w); k <= std::min(nx - 1, x + w); ++k) m = std::min(m, g[y * nx + k]);
      tmp[y * nx + x] = m;
    }
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      float m = std::numeric_limits<float>::infinity();
      for (int k = std::max(0, y - w); k <= std::min(ny - 1, y + w); ++k) m = std::min(m, tmp[k * nx + x]);
      out[y * nx + x] = m;
    }
  return out;
}

// Ground that follows slopes: cells whose candidate is the lower envelope (the minimum over
// their window) seed it; it grows to 8-neighbours whose candidate lies within max_step of the
// ground cell beside them (slopes up to max_step per cell, curbs) and at most max_rise above
// the envelope (a car's curved side would otherwise let it climb the body); object cells (roofs, car
// bodies, walls) differ by more and take the ground of the nearest ground cell instead.
std::vector<float> growGround(const std::vector<float>& cand, const std::vector<float>& envelope, int nx, int ny,
                              double max_step, double max_rise) {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> ground(cand.size(), inf);
  std::vector<int> queue;
  queue.reserve(cand.size());
  for (std::size_t c = 0; c < cand.size(); ++c)
    if (std::isfinite(cand[c]) && cand[c] <= envelope[c] + 0.02f) ground[c] = cand[c], queue.push_back(static_cast<int>(c));
  auto neighbours = [&](int c, auto&& f) {
    const int x = c % nx, y = c / nx;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int u = x + dx, v = y + dy;
        if ((dx || dy) && u >= 0 && v >= 0 && u < nx && v < ny) f(v * nx + u);
      }
  };
  for (std::size_t k = 0; k < queue.size(); ++k) {
    const int c = queue[k];
    neighbours(c, [&](int n) {
      if (std::isfinite(ground[n]) || !std::isfinite(cand[n]) || std::abs(cand[n] - ground[c]) > max_step ||
          cand[n] > envelope[n] + max_rise)
        return;
      ground[n] = cand[n];
      queue.push_back(n);
    });
  }
  // Every other cell: the ground of the nearest ground cell (breadth first over the grid).
  std::vector<float> out = ground;
  for (std::size_t k = 0; k < queue.size(); ++k) {
    const int c = queue[k];
    neighbours(c, [&](int n) {
      if (std::isfinite(out[n])) return;
      out[n] = out[c];
      queue.push_back(n);
    });
  }
  for (std::size_t c = 0; c < out.size(); ++c)
    if (!std::isfinite(out[c])) out[c] = envelope[c];
  return out;
}
}  // namespace

float SeenGround::at(double x, double y) const {
  const double cx = std::floor((x - min_x_) * inv_cell_), cy = std::floor((y - min_y_) * inv_cell_);
  if (!(cx >= 0 && cy >= 0 && cx < nx_ && cy < ny_)) return std::numeric_limits<float>::quiet_NaN();
  return z_[static_cast<std::size_t>(cy) * nx_ + static_cast<std::size_t>(cx)];
}

std::vector<float> heightAboveGround(const Cloud& cloud, const GroundParams& params, SeenGround* seen) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> h(cloud.size(), nan);
  float min_x = std::numeric_limits<float>::infinity(), min_y = min_x, max_x = -min_x, max_y = -min_x;
  const double r2 = params.max_range * params.max_range;
  std::vector<char> use(cloud.size(), 0);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const auto& p = cloud[i];
    if (!p.allFinite() || double(p.x()) * p.x() + double(p.y()) * p.y() > r2) continue;
    use[i] = 1;
    min_x = std::min(min_x, p.x());
    min_y = std::min(min_y, p.y());
    max_x = std::max(max_x, p.x());
    max_y = std::max(max_y, p.y());
  }
  if (!(min_x <= max_x)) return h;
  const double inv = 1.0 / params.cell;
  const int nx = static_cast<int>((max_x - min_x) * inv) + 1, ny = static_cast<int>((max_y - min_y) * inv) + 1;
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> lowest(static_cast<std::size_t>(nx) * ny, inf), second(lowest.size(), inf);
  std::vector<int> count(lowest.size(), 0);
  std::vector<int> cell_of(cloud.size(), -1);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!use[i]) continue;
    const auto& p = cloud[i];
    const int cx = std::min(nx - 1, static_cast<int>((p.x() - min_x) * inv));
    const int cy = std::min(ny - 1, static_cast<int>((p.y() - min_y) * inv));
    const int c = cy * nx + cx;
    cell_of[i] = c;
    ++count[c];
    if (p.z() < lowest[c]) {
      second[c] = lowest[c];
      lowest[c] = p.z();
    } else if (p.z() < second[c]) {
      second[c] = p.z();
    }
  }
  // A cell's ground candidate is its second-lowest point, robust to one stray low return.
  std::vector<float> cand(lowest.size(), inf);
  for (std::size_t c = 0; c < cand.size(); ++c)
    if (count[c] >= std::max(2, params.min_cell_points)) cand[c] = second[c];
  std::vector<float> envelope = minFilter(cand, nx, ny, params.window);
  // Returns from under the ground are no ground: a beam reflected off a wet road or a window
  // comes back late, from metres below the road (real SemanticKITTI 001500: 23 returns 3.5 m
  // under the road in front of a car), and would sink the envelope over a whole window. The
  // line of sight from the sensor (the origin) to such a return runs under the ground nearer
  // along it; to anything seen directly it does not. A cell that sets the envelope and whose
  // line of sight passes more than under_tolerance below the ground of a nearer cell is left
  // out, and the envelope is taken again, until none is. Ground there: the envelope of a cell
  // out of reach of the tested cell's window, below the sensor (crowns and roofs overhead are
  // no ground), where the cell's own candidate is ground (within `threshold` of it).
  auto cellOf = [&](double x, double y) {
    const int cx = static_cast<int>(std::floor((x - min_x) * inv)), cy = static_cast<int>(std::floor((y - min_y) * inv));
    return cx < 0 || cy < 0 || cx >= nx || cy >= ny ? -1 : cy * nx + cx;
  };
  // After the first round only cells within a window of a dropped one can have changed.
  std::vector<char> check(params.under_tolerance > 0 ? cand.size() : 0, 1);
  for (int round = 0; params.under_tolerance > 0 && round < 16; ++round) {
    std::vector<int> dropped;
    for (int c = 0; c < nx * ny; ++c) {
      if (!check[c] || !std::isfinite(cand[c]) || cand[c] > envelope[c]) continue;
      const double x = min_x + ((c % nx) + 0.5) * params.cell, y = min_y + ((c / nx) + 0.5) * params.cell;
      const double r = std::hypot(x, y);
      for (double s = params.cell; s < r - (params.window + 1.5) * params.cell; s += 2 * params.cell) {
        const int n = cellOf(x * s / r, y * s / r);
        if (n >= 0 && envelope[n] < 0 && cand[n] <= envelope[n] + params.threshold && cand[c] * s / r < envelope[n] - params.under_tolerance) {
          cand[c] = inf;
          dropped.push_back(c);
          break;
        }
      }
    }
    if (dropped.empty()) break;
    envelope = minFilter(cand, nx, ny, params.window);
    std::fill(check.begin(), check.end(), 0);
    for (int c : dropped)
      for (int v = std::max(0, c / nx - params.window); v <= std::min(ny - 1, c / nx + params.window); ++v)
        for (int u = std::max(0, c % nx - params.window); u <= std::min(nx - 1, c % nx + params.window); ++u) check[v * nx + u] = 1;
  }
  const std::vector<float> ground = params.max_step > 0 ? growGround(cand, envelope, nx, ny, params.max_step, params.max_rise) : envelope;
  if (seen) {
    seen->min_x_ = min_x, seen->min_y_ = min_y, seen->inv_cell_ = inv, seen->nx_ = nx, seen->ny_ = ny;
    seen->z_.assign(cand.size(), std::numeric_limits<float>::quiet_NaN());
    for (std::size_t c = 0; c < cand.size(); ++c)
      if (std::isfinite(cand[c]) && cand[c] <= ground[c] + params.threshold) seen->z_[c] = cand[c];
  }
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (cell_of[i] < 0) continue;
    float g = ground[cell_of[i]];
    if (!std::isfinite(g)) g = lowest[cell_of[i]];
    h[i] = cloud[i].z() - g;
  }
  return h;
}

}  // namespace slide::frontend
