// Hungarian assignment against brute force over all assignments on small random matrices.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "assignment/hungarian.h"

using namespace slide;

namespace {
// Best (pairs, cost) over all injective maps of the smaller side, pairs above max_cost
// excluded: maximal number of allowed pairs first, then minimal cost.
std::pair<int, double> bruteForce(const Eigen::MatrixXd& c, double max_cost) {
  const bool wide = c.rows() <= c.cols();
  const Eigen::MatrixXd a = wide ? c : Eigen::MatrixXd(c.transpose());
  std::vector<int> cols(a.cols());
  std::iota(cols.begin(), cols.end(), 0);
  std::pair<int, double> best{-1, 0};
  do {
    int pairs = 0;
    double cost = 0;
    for (int r = 0; r < a.rows(); ++r)
      if (a(r, cols[r]) <= max_cost) ++pairs, cost += a(r, cols[r]);
    if (pairs > best.first || (pairs == best.first && cost < best.second - 1e-12)) best = {pairs, cost};
  } while (std::next_permutation(cols.begin(), cols.end()));
  return best;
}

std::pair<int, double> score(const Eigen::MatrixXd& c, const std::vector<int>& a, double max_cost) {
  std::pair<int, double> s{0, 0};
  std::vector<int> used(c.cols(), 0);
  for (int r = 0; r < c.rows(); ++r) {
    if (a[r] < 0) continue;
    EXPECT_LT(a[r], c.cols());
    EXPECT_EQ(used[a[r]]++, 0) << "column used twice";
    EXPECT_LE(c(r, a[r]), max_cost);
    ++s.first;
    s.second += c(r, a[r]);
  }
  return s;
}
}  // namespace

TEST(Hungarian, MatchesBruteForceOnRandomSquareAndRectangular) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  for (int trial = 0; trial < 300; ++trial) {
    const int rows = 1 + trial % 6, cols = 1 + (trial / 6) % 6;
    Eigen::MatrixXd c(rows, cols);
    for (int i = 0; i < c.size(); ++i) c.data()[i] = std::round(u(rng) * 4) / 4;  // ties happen
    const auto a = assignment::solveAssignment(c);
    ASSERT_EQ(static_cast<int>(a.size()), rows);
    const auto s = score(c, a, 1e9);
    const auto b = bruteForce(c, 1e9);
    EXPECT_EQ(s.first, std::min(rows, cols));
    EXPECT_NEAR(s.second, b.second, 1e-9) << "trial " << trial;
  }
}

TEST(Hungarian, GatedMatchesBruteForce) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  for (int trial = 0; trial < 300; ++trial) {
    const int rows = 1 + trial % 5, cols = 1 + (trial / 5) % 6;
    Eigen::MatrixXd c(rows, cols);
    for (int i = 0; i < c.size(); ++i) c.data()[i] = u(rng);
    const double gate = 4.0;
    const auto s = score(c, assignment::solveGatedAssignment(c, gate), gate);
    const auto b = bruteForce(c, gate);
    EXPECT_EQ(s.first, b.first) << "trial " << trial;
    EXPECT_NEAR(s.second, b.second, 1e-9) << "trial " << trial;
  }
}

TEST(Hungarian, KnownCaseAndEdgeCases) {
  Eigen::MatrixXd c(3, 3);
  c << 4, 1, 3, 2, 0, 5, 3, 2, 2;
  EXPECT_EQ(assignment::solveAssignment(c), (std::vector<int>{1, 0, 2}));  // 1 + 2 + 2 = 5
  EXPECT_TRUE(assignment::solveAssignment(Eigen::MatrixXd(0, 3)).empty());
  EXPECT_EQ(assignment::solveAssignment(Eigen::MatrixXd(2, 0)), (std::vector<int>{-1, -1}));
  Eigen::MatrixXd bad(1, 1);
  bad << std::nan("");
  EXPECT_THROW(assignment::solveAssignment(bad), std::invalid_argument);
  // Gated: everything forbidden gives no pairs; infinities count as forbidden.
  Eigen::MatrixXd far(2, 2);
  far << 9, std::numeric_limits<double>::infinity(), 9, 9;
  EXPECT_EQ(assignment::solveGatedAssignment(far, 1.0), (std::vector<int>{-1, -1}));
}
