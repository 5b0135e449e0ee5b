#pragma once
// Minimum-cost assignment of rows to columns (Hungarian method, O(n^3)), private to the
// back-end's data association. Entries >= kForbidden are never assigned.
#include <Eigen/Core>
#include <vector>

namespace slide::backend {

inline constexpr double kForbidden = 1e9;

// For each row, the assigned column or -1. Rows and columns may differ in number.
std::vector<int> minCostAssignment(const Eigen::MatrixXd& cost);

}  // namespace slide::backend
