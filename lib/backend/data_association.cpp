#include "backend/data_association.h"

#include "assignment/hungarian.h"
#include "objects/association.h"

#include <algorithm>
#include <cmath>
#include <Eigen/Cholesky>

namespace slide::backend {

double associationCost(const Object& detection, const Object& landmark, const ClassTable& classes, double slack) {
  if (!classes.sameKind(detection.class_id, landmark.class_id)) return -1;
  const ClassInfo* c = classes.gateClass(detection.class_id, landmark.class_id);
  if (!c) return -1;
  if (c->association_max_slack > 0) slack = std::min(slack, c->association_max_slack);
  const double d = associationDistance(detection, landmark) / (c->association_distance + slack);
  const double m = modelDifference(detection, landmark) / c->model_difference;
  if (!(d <= 1.0) || !(m <= 1.0)) return -1;
  const auto* bd = std::get_if<Cuboid>(&detection.model);
  const auto* bl = std::get_if<Cuboid>(&landmark.model);
  if (bd && bl && !footprintsOverlap(*bd, *bl, 0.5 * slack)) return -1;
  return d + m;
}

double associationCost(const Detection& det, const Object& landmark, const ClassTable& classes) {
  const double metric = associationCost(det.object, landmark, classes, det.slack);
  if (metric < 0 || det.covariance.isZero()) return metric;
  const ClassInfo& c = *classes.gateClass(det.object.class_id, landmark.class_id);
  const Eigen::Matrix2d S =
      det.covariance + 0.25 * c.association_distance * c.association_distance * Eigen::Matrix2d::Identity();
  const Eigen::Vector2d d = (landmark.position() - det.object.position()).head<2>();
  const double m = std::sqrt(d.dot(S.ldlt().solve(d)));
  if (m > det.gate) return -1;
  return m / det.gate + modelDifference(det.object, landmark) / c.model_difference;
}

std::vector<int> associateDetections(const std::vector<Detection>& detections,
                                     const std::vector<LandmarkCandidate>& candidates, const ClassTable& classes) {
  std::vector<int> result(detections.size(), -1);
  if (detections.empty() || candidates.empty()) return result;
  // Pairs outside the gates cost kNotAllowed and are never assigned; among the allowed ones,
  // as many detections as possible are associated, at the least total cost.
  constexpr double kNotAllowed = 1e9;
  Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(detections.size(), candidates.size(), kNotAllowed);
  bool any = false;
  for (std::size_t i = 0; i < detections.size(); ++i)
    for (std::size_t j = 0; j < candidates.size(); ++j) {
      const double c = associationCost(detections[i], *candidates[j].object, classes);
      if (c >= 0) {
        cost(i, j) = c;
        any = true;
      }
    }
  if (!any) return result;
  const std::vector<int> assigned = assignment::solveGatedAssignment(cost, 0.5 * kNotAllowed);
  for (std::size_t i = 0; i < detections.size(); ++i)
    if (assigned[i] >= 0) result[i] = candidates[assigned[i]].index;
  return result;
}

}  // namespace slide::backend
