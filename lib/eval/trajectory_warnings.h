#pragma once
// Warnings on trajectory figures that are finite but mean little: a sim3 alignment whose scale
// collapsed (the estimate shrunk to a point fits anything) or exploded, and an association
// that covers only a small part of the reference trajectory.
#include <cstddef>
#include <optional>
#include <string>

namespace slide::eval {

struct TrajectoryWarningLimits {
  double min_scale = 0.5, max_scale = 2.0;  // a sim3 scale outside this range has collapsed / exploded
  double min_reference_fraction = 0.2;      // fewer reference poses associated: the error covers a fraction
};

// The warning for an alignment scale (sim3; other alignments keep scale 1), or none.
std::optional<std::string> scaleWarning(double scale, const TrajectoryWarningLimits& limits = {});

// The warning when `matched` pose pairs are few: under half of the smaller trajectory (the stamps
// do not line up), or under min_reference_fraction of the reference's poses; or none.
std::optional<std::string> coverageWarning(std::size_t matched, std::size_t n_est, std::size_t n_ref,
                                           const TrajectoryWarningLimits& limits = {});

}  // namespace slide::eval
