#pragma once
// One scan's fitted objects scored against its SemanticKITTI labels, without merging or
// otherwise helping the estimates.
//
// Ground truth, defined from the labels alone (no segmenter threshold enters):
//  - cars: every labelled instance of a cuboid class with at least min_car_points points;
//  - columns: the points labelled with a cylinder class (trunk, pole, sign), which carry no
//    instance ids, grouped by 3-D grid clustering (cell column_cell); every group of at least
//    min_column_points points is one target.
//  - others: the points labelled with one of SemanticKITTI's thing classes that no class of
//    ours holds (other_labels: bicycles, people, buses, trucks, other objects...), grouped as
//    columns are; ellipsoid estimates are scored against them (other_match metres).
// Each estimate of a shape is matched to at most one target of that shape (nearest first,
// horizontal distance of the estimate's position to the target's point centroid within
// car_match / column_match / other_match metres). A car counts as found only by a car-sized cuboid (every
// extent inside the class's size range). An estimate left over is
//  - a duplicate when it lies within the match distance of a target already taken,
//  - small when it lies within the match distance of labelled points of its shape that form
//    no target (a real object seen by too few points to be ground truth),
//  - false otherwise.
#include <string>
#include <vector>

#include "io/kitti_scan.h"
#include "objects/class_table.h"
#include "objects/object.h"

namespace slide::eval {

struct ScanScoreParams {
  int min_car_points = 200;
  int min_column_points = 30;
  double column_cell = 0.3;
  double car_match = 2.0;     // metres
  double column_match = 1.0;  // metres
  double other_match = 1.0;   // metres
  // SemanticKITTI thing classes an "other" ellipsoid stands for: bicycle, bus, motorcycle,
  // on-rails, truck, other-vehicle, person, bicyclist, motorcyclist, other-object and their
  // moving variants (cars, trunks, poles and signs belong to classes of their own).
  std::vector<int> other_labels{11, 13, 15, 16, 18, 20, 30, 31, 32, 99, 253, 254, 255, 256, 257, 258, 259};
  int other_class = 0;        // our class id the other targets carry
};

struct LabelledTarget {
  int class_id = 0;       // our class id
  int instance = 0;       // SemanticKITTI instance id (0 for columns)
  int points = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  int estimate = -1;      // index of the matched estimate, -1 when missed
  double distance = 0;    // of the match
};

enum class EstimateVerdict { Matched, Duplicate, Small, False };
const char* verdictName(EstimateVerdict v);

struct ShapeTally {
  int targets = 0, found = 0, estimates = 0, duplicates = 0, small = 0, false_estimates = 0;
};

struct ScanScore {
  std::vector<LabelledTarget> targets;
  std::vector<EstimateVerdict> verdicts;  // one per estimate
  ShapeTally cars, columns, others;
  int wrong_size_cuboids = 0;  // cuboids near a car target that are not car-sized
};

// Throws std::invalid_argument when the scan carries no labels.
ScanScore scoreScanAgainstLabels(const io::LabelledScan& scan, const std::vector<Object>& estimates,
                                 const ClassTable& classes, const ScanScoreParams& params = {});

}  // namespace slide::eval
