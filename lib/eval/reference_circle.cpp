#include "eval/reference_circle.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "frontend/circle_fit.h"

namespace slide::eval {

std::optional<ReferenceCircle> referenceCircle(const std::vector<Eigen::Vector2d>& pts, int trials, std::uint64_t seed) {
  const std::size_t n = pts.size();
  if (n < 5) return std::nullopt;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  std::vector<double> r2(n);
  double best_med = std::numeric_limits<double>::infinity();
  frontend::Circle best;
  for (int t = 0; t < trials; ++t) {
    const std::size_t i = pick(rng), j = pick(rng), k = pick(rng);
    if (i == j || j == k || i == k) continue;
    const auto c = frontend::circleThrough(pts[i], pts[j], pts[k]);
    if (!c) continue;
    for (std::size_t m = 0; m < n; ++m) {
      const double e = (pts[m] - c->center).norm() - c->radius;
      r2[m] = e * e;
    }
    std::nth_element(r2.begin(), r2.begin() + n / 2, r2.end());
    if (r2[n / 2] < best_med) best_med = r2[n / 2], best = *c;
  }
  if (!std::isfinite(best_med)) return std::nullopt;
  // Rousseeuw's scale of the least-median fit (3 parameters).
  const double sigma = 1.4826 * (1.0 + 5.0 / static_cast<double>(n - 3)) * std::sqrt(best_med);
  std::vector<Eigen::Vector2d> in;
  for (const auto& p : pts)
    if (std::abs((p - best.center).norm() - best.radius) <= 2.5 * sigma) in.push_back(p);
  const auto lsq = frontend::fitCircleAlgebraic(in);
  if (!lsq) return std::nullopt;
  return ReferenceCircle{lsq->center, lsq->radius, static_cast<int>(in.size()), sigma};
}

}  // namespace slide::eval
