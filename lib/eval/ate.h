#pragma once
// Absolute trajectory error of matched pose pairs after alignment.
#include <vector>

#include "eval/alignment.h"

namespace slide::eval {

struct AteResult {
  double rmse = 0, mean = 0, median = 0, max = 0;
  std::vector<double> errors;  // per pose, metres
  AlignmentResult alignment;
};

// est[i] and ref[i] are the same instant; translation errors after aligning est onto ref.
AteResult absoluteTrajectoryError(const std::vector<Pose>& est, const std::vector<Pose>& ref,
                                  TrajectoryAlignment mode = TrajectoryAlignment::Se3);

}  // namespace slide::eval
