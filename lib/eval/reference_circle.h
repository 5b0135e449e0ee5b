#pragma once
// A reference circle for a real trunk slice that also holds other things (a branch, leaves):
// least median of squares over circles through three of its points (the circle whose median
// squared residual is least: it ignores up to half the points), then algebraic least squares
// over the points within 2.5 robust sigmas of it. Independent of the project's trunk fit
// (frontend/shape_fit.h: slices, RANSAC bands, spread estimates; only the textbook circle
// primitives of frontend/circle_fit.h are shared), so a benchmark can score that fit against it.
// Deterministic (seeded).
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace slide::eval {

struct ReferenceCircle {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0;
  int inliers = 0;     // points the least-squares refit used
  double sigma = 0;    // robust residual scale of the least-median circle (metres)
};

// nullopt for fewer than 5 points or when no three points make a circle.
std::optional<ReferenceCircle> referenceCircle(const std::vector<Eigen::Vector2d>& pts, int trials = 3000,
                                               std::uint64_t seed = 1);

}  // namespace slide::eval
