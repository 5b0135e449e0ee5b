#include "frontend/wall_trace.h"

#include <algorithm>
#include <cmath>

namespace slide::frontend {

namespace {
// Distance of c from the line through a and b (a != b).
float offLine(const Eigen::Vector2f& a, const Eigen::Vector2f& b, const Eigen::Vector2f& c) {
  const Eigen::Vector2f u = (b - a).normalized(), w = c - a;
  return std::abs(u.x() * w.y() - u.y() * w.x());
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
  // returns, at a regular spacing, longer than a column is wide.
  if (p.corner_run <= 0 || e.norm() < n1.norm() - p.line_tolerance) return false;
  for (std::size_t j = 1; j < n.size(); ++j) {
    const Eigen::Vector2f nj = xy(n[j]);
    const float step = (nj - xy(n[j - 1])).norm();
    if (step > p.max_step || step > p.max_step_ratio * s2 || s2 > p.max_step_ratio * step) return false;
    for (std::size_t k = 1; k < j; ++k)
      if (offLine(n1, nj, xy(n[k])) > p.line_tolerance) return false;
    if (j >= 2 && (nj - n1).norm() >= p.corner_run) return true;
  }
  return false;
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
