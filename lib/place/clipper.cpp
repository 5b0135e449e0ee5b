#include "place/clipper.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace slide::place {

namespace {
using Vec = std::vector<double>;

// Mu = u + W u (unit diagonal, weighted edges) and Bu = sum of u over neighbours.
void multiply(const ConsistencyGraph& g, const Vec& u, Vec& Mu, Vec& Bu) {
  const std::size_t m = g.size();
  for (std::size_t i = 0; i < m; ++i) {
    double wm = 0, bm = 0;
    const float* w = g.weightsBegin(i);
    for (const std::uint32_t* j = g.neighborsBegin(i); j != g.neighborsEnd(i); ++j, ++w) {
      wm += *w * u[*j];
      bm += u[*j];
    }
    Mu[i] = u[i] + wm;
    Bu[i] = bm;
  }
}

// Objective u'Mu - d u'Cu with Cu = sum(u) - u - Bu (the complement graph, never formed).
double objective(const Vec& u, const Vec& Mu, const Vec& Bu, double d) {
  const double s = std::accumulate(u.begin(), u.end(), 0.0);
  double f = 0;
  for (std::size_t i = 0; i < u.size(); ++i) f += u[i] * (Mu[i] - d * (s - u[i] - Bu[i]));
  return f;
}

// Projection onto {u >= 0, |u| = 1, u_i = 0 unless active}; false when nothing positive is left.
bool project(Vec& u, const std::vector<char>* active) {
  double n2 = 0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    double& x = u[i];
    x = (active && !(*active)[i]) ? 0.0 : std::max(0.0, x);
    n2 += x * x;
  }
  if (!(n2 > 0)) return false;
  const double inv = 1.0 / std::sqrt(n2);
  for (double& x : u) x *= inv;
  return true;
}
}  // namespace

ClipperResult solveClipper(const ConsistencyGraph& g, const ClipperParams& params, const std::vector<char>* active) {
  ClipperResult res;
  const std::size_t m = g.size();
  res.edges = g.numEdges();
  res.peak_bytes = g.peakBytes() + 6 * m * sizeof(double);
  if (m == 0 || (active && std::find(active->begin(), active->end(), 1) == active->end())) return res;

  std::mt19937 rng(params.seed);
  std::uniform_real_distribution<double> uni(0.1, 1.0);
  Vec u(m), Mu(m), Bu(m), grad(m), next(m), Mn(m), Bn(m);
  for (double& x : u) x = uni(rng);
  project(u, active);

  double d = 0;
  for (int outer = 0; outer < params.max_outer; ++outer) {
    res.outer_iterations = outer + 1;
    multiply(g, u, Mu, Bu);
    double f = objective(u, Mu, Bu, d);
    double alpha = 1.0;
    for (int inner = 0; inner < params.max_inner; ++inner) {
      const double s = std::accumulate(u.begin(), u.end(), 0.0);
      for (std::size_t i = 0; i < m; ++i) grad[i] = 2.0 * (Mu[i] - d * (s - u[i] - Bu[i]));
      // Backtracking line search on the projected step.
      bool improved = false;
      double fn = f;
      for (int tries = 0; tries < 30; ++tries, alpha *= 0.5) {
        for (std::size_t i = 0; i < m; ++i) next[i] = u[i] + alpha * grad[i];
        if (!project(next, active)) continue;
        multiply(g, next, Mn, Bn);
        fn = objective(next, Mn, Bn, d);
        if (fn > f) {
          improved = true;
          break;
        }
      }
      if (!improved) break;
      const double change = fn - f;
      u.swap(next);
      Mu.swap(Mn);
      Bu.swap(Bn);
      f = fn;
      alpha = std::min(alpha * 2.0, 1e6);
      if (change < params.tol_f * std::max(1.0, std::abs(f))) break;
    }
    // Inconsistent mass seen by each association of the support; done when there is none.
    const double umax = *std::max_element(u.begin(), u.end());
    const double cut = params.support_eps * umax;
    const double s = std::accumulate(u.begin(), u.end(), 0.0);
    double min_ratio = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < m; ++i) {
      if (u[i] <= cut) continue;
      const double cu = s - u[i] - Bu[i];
      if (cu > cut) min_ratio = std::min(min_ratio, Mu[i] / cu);
    }
    if (!std::isfinite(min_ratio)) break;
    d = std::max(2.0 * d, min_ratio);
  }
  multiply(g, u, Mu, Bu);
  res.density = std::inner_product(u.begin(), u.end(), Mu.begin(), 0.0);

  // Rounding: the top association, then its neighbours by decreasing u, each kept when
  // consistent with every association kept so far (the result is a clique).
  const std::size_t top = static_cast<std::size_t>(std::max_element(u.begin(), u.end()) - u.begin());
  std::vector<std::size_t> order;
  for (const std::uint32_t* j = g.neighborsBegin(top); j != g.neighborsEnd(top); ++j)
    if (!active || (*active)[*j]) order.push_back(*j);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return u[x] > u[y]; });
  res.selected.push_back(top);
  for (std::size_t c : order) {
    bool ok = true;
    for (std::size_t k : res.selected)
      if (!g.consistent(c, k)) {
        ok = false;
        break;
      }
    if (ok) res.selected.push_back(c);
  }
  std::sort(res.selected.begin(), res.selected.end());
  return res;
}

ClipperResult clipper(const std::vector<Eigen::Vector3d>& pa, const std::vector<Eigen::Vector3d>& pb,
                      const std::vector<Association>& assoc, const ClipperParams& params) {
  const ConsistencyGraph g(pa, pb, assoc, params.consistency);
  return solveClipper(g, params);
}

}  // namespace slide::place
