#include "frontend/circle_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>

namespace slide::frontend {

std::optional<Circle> circleThrough(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d ab = b - a, ac = c - a;
  const double d = 2.0 * (ab.x() * ac.y() - ab.y() * ac.x());
  if (std::abs(d) < 1e-12) return std::nullopt;
  const double ab2 = ab.squaredNorm(), ac2 = ac.squaredNorm();
  const Eigen::Vector2d u((ac.y() * ab2 - ab.y() * ac2) / d, (ab.x() * ac2 - ac.x() * ab2) / d);
  Circle circle;
  circle.center = a + u;
  circle.radius = u.norm();
  return circle;
}

namespace {

int countInliers(const std::vector<Eigen::Vector2d>& pts, const Circle& c, double thr, std::vector<Eigen::Vector2d>* out) {
  int n = 0;
  for (const auto& p : pts) {
    if (std::abs((p - c.center).norm() - c.radius) <= thr) {
      ++n;
      if (out) out->push_back(p);
    }
  }
  return n;
}
}  // namespace

std::optional<Circle> fitCircleAlgebraic(const std::vector<Eigen::Vector2d>& pts) {
  if (pts.size() < 3) return std::nullopt;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  // |q|^2 + D qx + E qy + F = 0 in coordinates q = p - mean, solved by linear least squares.
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Vector3d Atb = Eigen::Vector3d::Zero();
  for (const auto& p : pts) {
    const Eigen::Vector2d q = p - mean;
    const Eigen::Vector3d row(q.x(), q.y(), 1.0);
    AtA += row * row.transpose();
    Atb -= row * q.squaredNorm();
  }
  Eigen::LDLT<Eigen::Matrix3d> ldlt(AtA);
  if (ldlt.info() != Eigen::Success || std::abs(ldlt.vectorD().minCoeff()) < 1e-12 * std::max(1.0, AtA.trace()))
    return std::nullopt;
  const Eigen::Vector3d s = ldlt.solve(Atb);
  const Eigen::Vector2d c(-s[0] / 2.0, -s[1] / 2.0);
  const double r2 = c.squaredNorm() - s[2];
  if (!(r2 > 0) || !std::isfinite(r2)) return std::nullopt;
  Circle circle;
  circle.center = c + mean;
  circle.radius = std::sqrt(r2);
  circle.inliers = static_cast<int>(pts.size());
  return circle;
}

std::optional<Circle> fitCircleRansac(const std::vector<Eigen::Vector2d>& pts, const CircleRansacParams& params) {
  const int n = static_cast<int>(pts.size());
  if (n < 3) return std::nullopt;
  std::mt19937 rng(params.seed);
  std::uniform_int_distribution<int> pick(0, n - 1);
  std::optional<Circle> best;
  for (int it = 0; it < params.iterations; ++it) {
    const int i = pick(rng), j = pick(rng), k = pick(rng);
    if (i == j || j == k || i == k) continue;
    auto c = circleThrough(pts[i], pts[j], pts[k]);
    if (!c || c->radius < params.min_radius || c->radius > params.max_radius) continue;
    c->inliers = countInliers(pts, *c, params.inlier_distance, nullptr);
    if (!best || c->inliers > best->inliers) best = c;
  }
  if (!best) return std::nullopt;
  // Refit on the inliers twice; keep the refit only while it stays inside the radius bounds.
  for (int round = 0; round < 2; ++round) {
    std::vector<Eigen::Vector2d> in;
    countInliers(pts, *best, params.inlier_distance, &in);
    auto refit = fitCircleAlgebraic(in);
    if (!refit || refit->radius < params.min_radius || refit->radius > params.max_radius) break;
    refit->inliers = countInliers(pts, *refit, params.inlier_distance, nullptr);
    if (refit->inliers < best->inliers) break;
    best = refit;
  }
  // A surface smoother than the band (a terrestrial scan's bark, a few millimetres rough): the
  // band's outer part holds rough bark and the base of a branch, not the ring. One more refit
  // on the points within three robust sigmas of the inliers' residuals, when that is narrower.
  std::vector<double> res;
  for (const auto& p : pts)
    if (const double e = (p - best->center).norm() - best->radius; std::abs(e) <= params.inlier_distance) res.push_back(e);
  if (res.size() >= 10) {
    std::nth_element(res.begin(), res.begin() + res.size() / 2, res.end());
    const double med = res[res.size() / 2];
    for (double& e : res) e = std::abs(e - med);
    std::nth_element(res.begin(), res.begin() + res.size() / 2, res.end());
    const double band = 3.0 * 1.4826 * res[res.size() / 2];
    if (band < params.inlier_distance) {
      std::vector<Eigen::Vector2d> in;
      countInliers(pts, *best, band, &in);
      if (auto refit = fitCircleAlgebraic(in); refit && refit->radius >= params.min_radius && refit->radius <= params.max_radius) {
        refit->inliers = countInliers(pts, *refit, params.inlier_distance, nullptr);
        best = refit;
      }
    }
  }
  return best;
}

}  // namespace slide::frontend
