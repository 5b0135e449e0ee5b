#pragma once
// Detection-to-landmark association for one key pose: same class (or family, ClassInfo::family), centre distance and model
// difference inside the class table's thresholds, boxes whose footprints overlap, and at most one detection per landmark,
// chosen by a minimum-cost assignment (normalized distance + normalized model difference).
#include <vector>

#include "objects/class_table.h"

namespace slide::backend {

// A detection in the landmarks' frame, with the extra distance its own uncertainty allows
// (e.g. a few bearing sigmas times its range) on top of the class threshold. With a
// horizontal covariance (e.g. radial/tangential from a range-bearing sensor), pairs must
// also pass a Mahalanobis gate: |dxy|^2 in (covariance + (threshold/2)^2 I)^-1 <= gate^2,
// and the cost uses that distance instead of the metric one.
struct Detection {
  Object object;
  double slack = 0.0;
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();  // zero: metric gate only
  double gate = 3.0;
};

struct LandmarkCandidate {
  int index = -1;                  // caller's landmark index
  const Object* object = nullptr;  // landmark in the same frame as the detections
};

// Cost of pairing a detection with a landmark: distance / (class threshold + slack) + model
// difference / class threshold (each <= 1 when associable); negative when not associable,
// which includes two boxes whose footprints, grown by half the slack each, do not overlap.
double associationCost(const Object& detection, const Object& landmark, const ClassTable& classes, double slack = 0.0);
double associationCost(const Detection& detection, const Object& landmark, const ClassTable& classes);

// For each detection, the index of its landmark or -1 (a new landmark).
std::vector<int> associateDetections(const std::vector<Detection>& detections,
                                     const std::vector<LandmarkCandidate>& candidates, const ClassTable& classes);

}  // namespace slide::backend
