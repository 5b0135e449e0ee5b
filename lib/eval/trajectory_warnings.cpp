#include "eval/trajectory_warnings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace slide::eval {

std::optional<std::string> scaleWarning(double scale, const TrajectoryWarningLimits& limits) {
  if (std::isfinite(scale) && scale >= limits.min_scale && scale <= limits.max_scale) return std::nullopt;
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "sim3 scale %.6g is outside [%g, %g]: the alignment %s the estimate, so its error is meaningless "
                "(a scale near 0 fits any trajectory); check the estimate or align se3",
                scale, limits.min_scale, limits.max_scale,
                !std::isfinite(scale) ? "failed on" : scale < limits.min_scale ? "shrank" : "stretched");
  return std::string(buf);
}

std::optional<std::string> coverageWarning(std::size_t matched, std::size_t n_est, std::size_t n_ref,
                                           const TrajectoryWarningLimits& limits) {
  char buf[400];
  if (matched * 2 < std::min(n_est, n_ref)) {
    std::snprintf(buf, sizeof buf,
                  "only %zu of %zu estimate and %zu reference poses matched in time: check the stamps (KITTI poses "
                  "are stamped by frame index unless --est-times/--ref-times are given), --max-dt and --offset",
                  matched, n_est, n_ref);
    return std::string(buf);
  }
  if (static_cast<double>(matched) < limits.min_reference_fraction * static_cast<double>(n_ref)) {
    std::snprintf(buf, sizeof buf,
                  "only %zu of %zu reference poses (%.1f %%) are associated: the error covers that part of the "
                  "reference trajectory only",
                  matched, n_ref, n_ref ? 100.0 * static_cast<double>(matched) / static_cast<double>(n_ref) : 0.0);
    return std::string(buf);
  }
  return std::nullopt;
}

}  // namespace slide::eval
