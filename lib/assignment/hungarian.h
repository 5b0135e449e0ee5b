#pragma once
// Minimum-cost assignment (Hungarian algorithm, shortest augmenting paths with potentials,
// O(n^2 m)) for rectangular cost matrices.
#include <vector>

#include <Eigen/Core>

namespace slide::assignment {

// result[r] = column assigned to row r, or -1; min(rows, cols) rows get a column and the
// total cost is minimal. Costs must be finite.
std::vector<int> solveAssignment(const Eigen::MatrixXd& cost);

// Assignment where pairs costing more than `max_cost` are not allowed: first as many allowed
// pairs as possible, then the least total cost among those; rows left out get -1.
std::vector<int> solveGatedAssignment(const Eigen::MatrixXd& cost, double max_cost);

}  // namespace slide::assignment
