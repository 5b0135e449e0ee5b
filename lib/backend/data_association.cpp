#include "backend/data_association.h"

#include "backend/assignment.h"
#include "objects/association.h"

namespace slide {

double associationCost(const Object& detection, const Object& landmark, const ClassTable& classes, double slack) {
  if (detection.class_id != landmark.class_id) return -1;
  const ClassInfo* c = classes.find(detection.class_id);
  if (!c) return -1;
  const double d = associationDistance(detection, landmark) / (c->association_distance + slack);
  const double m = modelDifference(detection, landmark) / c->model_difference;
  if (!(d <= 1.0) || !(m <= 1.0)) return -1;
  return d + m;
}

std::vector<int> associateDetections(const std::vector<Detection>& detections,
                                     const std::vector<LandmarkCandidate>& candidates, const ClassTable& classes) {
  std::vector<int> result(detections.size(), -1);
  if (detections.empty() || candidates.empty()) return result;
  Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(detections.size(), candidates.size(), backend::kForbidden);
  bool any = false;
  for (std::size_t i = 0; i < detections.size(); ++i)
    for (std::size_t j = 0; j < candidates.size(); ++j) {
      const double c = associationCost(detections[i].object, *candidates[j].object, classes, detections[i].slack);
      if (c >= 0) {
        cost(i, j) = c;
        any = true;
      }
    }
  if (!any) return result;
  const std::vector<int> assigned = backend::minCostAssignment(cost);
  for (std::size_t i = 0; i < detections.size(); ++i)
    if (assigned[i] >= 0) result[i] = candidates[assigned[i]].index;
  return result;
}

}  // namespace slide
