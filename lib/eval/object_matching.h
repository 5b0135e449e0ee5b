#pragma once
// Object mapping quality against ground truth: one-to-one matching of estimated to true
// objects of the same class within a distance threshold, then precision, recall, F1 per
// class and overall, and the landmark position RMSE over matched pairs.
//
// Matching is greedy by distance (deterministic, documented choice): all same-class
// (estimate, truth) pairs closer than the threshold are sorted by distance and accepted
// nearest first when neither object is matched yet. Equal distances break by estimate
// index, then truth index. Greedy can differ from the minimum-cost assignment only when
// two candidates of one class compete within the threshold in a chain.
#include <cstddef>
#include <vector>

#include "objects/object.h"

namespace slide::eval {

struct ObjectMatchOptions {
  double threshold = 1.0;   // metres between object positions (Object::position())
  bool planar = false;      // distance in x, y only (maps whose heights are unreliable)
  // false: any class may match any class; a match then counts for the estimate's class, so
  // only the overall figures are meaningful (a class's recall can exceed 1).
  bool match_classes = true;
};

struct ObjectMatch {
  std::size_t est = 0, gt = 0;
  double distance = 0;
};

struct ClassScore {
  int class_id = -1;  // -1 for the overall (pooled) score
  std::size_t true_positives = 0, num_est = 0, num_gt = 0;
  // precision = TP / num_est, recall = TP / num_gt, F1 their harmonic mean; each is 0 when
  // its denominator is 0.
  double precision = 0, recall = 0, f1 = 0;
  double position_rmse = 0;  // metres over this class's matches (0 without matches)
};

struct ObjectMappingScore {
  ClassScore overall;                 // counts pooled over classes (micro average)
  std::vector<ClassScore> per_class;  // classes present in either map, by id
  std::vector<ObjectMatch> matches;   // ordered by estimate index
};

ObjectMappingScore scoreObjectMap(const std::vector<Object>& est, const std::vector<Object>& gt,
                                  const ObjectMatchOptions& opts = {});

// Per estimate of `est`: 1 when `score` (scoreObjectMap(est, gt, opts)) left it unmatched and
// it lies within the threshold of a true object of its class that another estimate took: the
// same object mapped twice. Unmatched estimates with no such neighbour are false objects.
std::vector<char> secondEstimates(const std::vector<Object>& est, const std::vector<Object>& gt,
                                  const ObjectMappingScore& score, const ObjectMatchOptions& opts = {});

}  // namespace slide::eval
