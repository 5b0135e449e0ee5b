#pragma once
// Circle fits in the plane: algebraic least squares (Kasa) and RANSAC with a least-squares
// refit on the inliers. Used on horizontal slices of trunks and poles.
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace slide::frontend {

struct Circle {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.0;
  int inliers = 0;  // points within the RANSAC threshold (all points for the algebraic fit)
};

// The circle through three points; nullopt when they are (nearly) collinear.
std::optional<Circle> circleThrough(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

// Algebraic least-squares circle (minimizes sum (|p-c|^2 - r^2)^2); nullopt for fewer than
// 3 points or (near-)collinear points.
std::optional<Circle> fitCircleAlgebraic(const std::vector<Eigen::Vector2d>& pts);

struct CircleRansacParams {
  int iterations = 60;
  double inlier_distance = 0.02;  // metres from the circle
  double min_radius = 0.02;
  double max_radius = 1.0;
  unsigned seed = 7;
};

// RANSAC over 3-point circles with radius bounds, then algebraic refits on the inliers.
std::optional<Circle> fitCircleRansac(const std::vector<Eigen::Vector2d>& pts, const CircleRansacParams& params);

}  // namespace slide::frontend
