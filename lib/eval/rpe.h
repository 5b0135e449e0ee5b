#pragma once
// Relative pose error (Sturm et al., as evo computes it): for pose pairs (i, j) a fixed
// distance apart, E = inv(inv(Q_i) Q_j) * inv(P_i) P_j with Q the reference, P the estimate;
// the translation error is |trans(E)| and the rotation error the angle of rot(E).
#include <cstddef>
#include <vector>

#include "eval/error_stats.h"
#include "geometry/pose.h"

namespace slide::eval {

enum class DeltaUnit { Frames, Metres };

struct RpeOptions {
  double delta = 1.0;                 // pair spacing: frames (integer >= 1) or metres travelled
  DeltaUnit unit = DeltaUnit::Frames;
  // Multiplies the estimate's translations first (the Sim3 scale for monocular-like runs).
  // A rigid alignment of the whole estimate cancels in relative poses and is not needed.
  double scale = 1.0;
};

struct RpeResult {
  ErrorStats translation;       // metres
  ErrorStats rotation_deg;      // degrees
  std::vector<double> trans_errors, rot_errors_deg;
  std::vector<std::size_t> first, second;  // indices of each pair
};

// est[i] and ref[i] are the same instant. In metres, a pair is (i, j) with j the first index
// whose reference path length from i reaches delta. Throws std::invalid_argument on
// different lengths or a bad delta; gives an empty result when no pair fits.
RpeResult relativePoseError(const std::vector<Pose>& est, const std::vector<Pose>& ref, const RpeOptions& opts = {});

// Length of the polyline through the poses' positions.
double pathLength(const std::vector<Pose>& poses);

}  // namespace slide::eval
