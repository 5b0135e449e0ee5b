#include "assignment/hungarian.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace slide::assignment {

namespace {
// Rows <= cols. 1-based arrays as in the textbook formulation: p[j] is the row matched to
// column j, u/v are the row and column potentials.
std::vector<int> solveWide(const Eigen::MatrixXd& a) {
  const int n = static_cast<int>(a.rows()), m = static_cast<int>(a.cols());
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0), v(m + 1, 0);
  std::vector<int> p(m + 1, 0), way(m + 1, 0);
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(m + 1, inf);
    std::vector<char> used(m + 1, 0);
    do {
      used[j0] = 1;
      const int i0 = p[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double cur = a(i0 - 1, j - 1) - u[i0] - v[j];
        if (cur < minv[j]) minv[j] = cur, way[j] = j0;
        if (minv[j] < delta) delta = minv[j], j1 = j;
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) u[p[j]] += delta, v[j] -= delta;
        else minv[j] -= delta;
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      const int j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> row_to_col(n, -1);
  for (int j = 1; j <= m; ++j)
    if (p[j] != 0) row_to_col[p[j] - 1] = j - 1;
  return row_to_col;
}
}  // namespace

std::vector<int> solveAssignment(const Eigen::MatrixXd& cost) {
  if (!cost.allFinite()) throw std::invalid_argument("solveAssignment: cost matrix has non-finite entries");
  if (cost.rows() == 0 || cost.cols() == 0) return std::vector<int>(cost.rows(), -1);
  if (cost.rows() <= cost.cols()) return solveWide(cost);
  const std::vector<int> col_to_row = solveWide(cost.transpose());
  std::vector<int> row_to_col(cost.rows(), -1);
  for (int c = 0; c < static_cast<int>(col_to_row.size()); ++c)
    if (col_to_row[c] >= 0) row_to_col[col_to_row[c]] = c;
  return row_to_col;
}

std::vector<int> solveGatedAssignment(const Eigen::MatrixXd& cost, double max_cost) {
  // A forbidden pair costs more than any set of allowed pairs could, so the solver first
  // maximizes the number of allowed pairs; forbidden pairs it still makes are dropped.
  double allowed_sum = 0;
  for (Eigen::Index i = 0; i < cost.size(); ++i) {
    const double c = cost.data()[i];
    if (std::isfinite(c) && c <= max_cost) allowed_sum += std::abs(c);
  }
  const double forbidden = 2.0 * allowed_sum + 1.0;
  Eigen::MatrixXd gated = cost;
  for (Eigen::Index i = 0; i < gated.size(); ++i) {
    double& c = gated.data()[i];
    if (!std::isfinite(c) || c > max_cost) c = forbidden;
  }
  std::vector<int> a = solveAssignment(gated);
  for (int r = 0; r < static_cast<int>(a.size()); ++r)
    if (a[r] >= 0 && gated(r, a[r]) >= forbidden) a[r] = -1;
  return a;
}

}  // namespace slide::assignment
