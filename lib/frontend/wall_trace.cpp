#include "frontend/wall_trace.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace slide::frontend {

namespace {
// Distance of c from the line through a and b (a != b).
float offLine(const Eigen::Vector2f& a, const Eigen::Vector2f& b, const Eigen::Vector2f& c) {
  const Eigen::Vector2f u = (b - a).normalized(), w = c - a;
  return std::abs(u.x() * w.y() - u.y() * w.x());
}

// Do pts[first], pts[first + 1], ... (returns of one beam, in azimuth order) begin a straight run
// of at least three returns that reaches corner_run metres? Straight: every return within
// line_tolerance of the least-squares line through the run (a line through two noisy returns
// tilts by their range noise); regular: each step along that line is positive, at most
// max_step, and within max_step_ratio of the run's median step.
bool straightRun(const std::vector<Eigen::Vector2f>& pts, std::size_t first, const WallTraceParams& p) {
  for (std::size_t last = first + 2; last < pts.size(); ++last) {
    if ((pts[last] - pts[first]).norm() < p.corner_run) continue;
    const int m = static_cast<int>(last - first + 1);
    Eigen::Vector2f mean = Eigen::Vector2f::Zero();
    for (std::size_t k = first; k <= last; ++k) mean += pts[k];
    mean /= static_cast<float>(m);
    Eigen::Matrix2f cov = Eigen::Matrix2f::Zero();
    for (std::size_t k = first; k <= last; ++k) cov += (pts[k] - mean) * (pts[k] - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2f> eig(cov);
    Eigen::Vector2f u = eig.eigenvectors().col(1);
    if (u.dot(pts[last] - pts[first]) < 0) u = -u;
    std::vector<float> steps;
    for (std::size_t k = first; k <= last; ++k) {
      const Eigen::Vector2f w = pts[k] - mean;
      if (std::abs(u.x() * w.y() - u.y() * w.x()) > p.line_tolerance) return false;
      if (k > first) steps.push_back(u.dot(pts[k] - pts[k - 1]));
    }
    std::vector<float> sorted = steps;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const float median = sorted[sorted.size() / 2];
    for (float s : steps)
      if (s <= 0 || s > p.max_step || s > p.max_step_ratio * median || median > p.max_step_ratio * s) return false;
    return true;
  }
  return false;
}

// Does the scan line continue beyond `edge` (direction +1: growing azimuth) as a face?
bool continuesAsFace(const Cloud& cloud, const ScanLines& lines, int edge, int direction, const std::vector<char>& in_column,
                     const WallTraceParams& p) {
  const Eigen::Vector2f e = cloud[edge].head<2>();
  const double window = std::min(10.0, std::max(p.window_deg, p.window_length / std::max(0.1f, e.norm()) * 180.0 / M_PI));
  const std::vector<int> n =
      lines.next(edge, direction, p.corner_run > 0 ? p.max_run_returns : 2, window, p.beam_tolerance_deg, in_column);
  if (n.size() < 2) return false;
  auto xy = [&](int i) { return Eigen::Vector2f(cloud[i].head<2>()); };
  const Eigen::Vector2f n1 = xy(n[0]), n2 = xy(n[1]);
  const float s1 = (n1 - e).norm(), s2 = (n2 - n1).norm();
  if (s1 > p.max_step || s2 > p.max_step || s1 < 1e-3f || s2 < 1e-3f) return false;
  // Straight on: the edge lies on the line of the next two, at a regular spacing.
  if (s1 <= p.max_step_ratio * s2 && s2 <= p.max_step_ratio * s1 && (n1 - e).dot(n2 - n1) > 0 &&
      offLine(n1, n2, e) <= p.line_tolerance)
    return true;
  // Round a corner: the edge lies behind the first of a straight run of at least three
  // returns, at a regular spacing, longer than a column is wide. The run may begin one return
  // later: a wall's end face (its thickness, seen at a grazing angle) gives one return off the
  // line of the face beside it.
  if (p.corner_run <= 0 || e.norm() < n1.norm() - p.line_tolerance) return false;
  std::vector<Eigen::Vector2f> run;
  for (int i : n) run.push_back(xy(i));
  return straightRun(run, 0, p) || (e.norm() >= run[1].norm() - p.line_tolerance && straightRun(run, 1, p));
}

// Is `edge`, the only return of its beam in the column, a stack between two others on one
// line: its nearest returns on either side in azimuth, on the same beam, at a regular spacing?
bool betweenOnALine(const Cloud& cloud, const ScanLines& lines, int edge, const std::vector<char>& in_column,
                    const WallTraceParams& p) {
  const Eigen::Vector2f e = cloud[edge].head<2>();
  const double window = std::min(10.0, std::max(p.window_deg, p.window_length / std::max(0.1f, e.norm()) * 180.0 / M_PI));
  const std::vector<int> a = lines.next(edge, +1, 1, window, p.beam_tolerance_deg, in_column);
  const std::vector<int> b = lines.next(edge, -1, 1, window, p.beam_tolerance_deg, in_column);
  if (a.empty() || b.empty()) return false;
  const Eigen::Vector2f na = cloud[a[0]].head<2>(), nb = cloud[b[0]].head<2>();
  const float sa = (na - e).norm(), sb = (nb - e).norm();
  if (sa > p.max_step || sb > p.max_step || sa < 1e-3f || sb < 1e-3f) return false;
  if (sa > p.max_step_ratio * sb || sb > p.max_step_ratio * sa || (na - e).dot(e - nb) <= 0) return false;
  return offLine(na, nb, e) <= p.line_tolerance;
}

}  // namespace

double faceFraction(const Cloud& cloud, const ScanLines& lines, const std::vector<int>& column,
                    const std::vector<char>& in_column, const WallTraceParams& p) {
  const std::vector<ScanLines::BeamEdges> beams = lines.beamEdges(column, p.beam_tolerance_deg);
  if (beams.empty()) return 0.0;
  const int n = static_cast<int>(beams.size());
  int faces = 0, seen = 0;
  for (const auto& b : beams) {
    faces += continuesAsFace(cloud, lines, b.high, +1, in_column, p) || continuesAsFace(cloud, lines, b.low, -1, in_column, p) ||
             (b.low == b.high && betweenOnALine(cloud, lines, b.low, in_column, p));
    ++seen;
    // Decided against min_fraction either way: the rest cannot change the verdict.
    if (p.min_fraction > 0 && (faces >= p.min_fraction * n || faces + (n - seen) < p.min_fraction * n)) break;
  }
  return static_cast<double>(faces) / n;
}

}  // namespace slide::frontend
