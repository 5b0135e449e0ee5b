#pragma once
// Test and benchmark helper: a copy of a landmark map as another robot would hold it — in its
// own frame, with position noise and some objects missed (errors of estimates: eval/transform_error.h).
#include <random>

#include "place/landmark.h"

namespace slide::place {

struct PerturbParams {
  double position_sigma = 0.05;  // metres, per axis
  double size_sigma = 0.0;       // metres, per extent
  double drop_fraction = 0.0;    // chance of leaving each landmark out
};

// Landmarks of `a` expressed in frame B (T_a_b maps B into A), perturbed. Each output landmark
// keeps the `index` of the landmark it copies (ground truth for checking matches).
std::vector<Landmark> perturbedCopy(const std::vector<Landmark>& a, const Pose& T_a_b, const PerturbParams& p,
                                    std::mt19937& rng);

}  // namespace slide::place
