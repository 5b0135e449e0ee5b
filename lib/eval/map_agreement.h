#pragma once
// How two robots' object maps agree, as the paper judges inter-robot transforms: the best rigid
// alignment of the two maps over the real objects both hold, and the distances between the two
// robots' landmarks of one object once a transform places one map in the other's frame. The
// ground truth only pairs the landmarks (each map, placed in the world through its robot's true
// start, is matched one-to-one to it); positions stay in each robot's own frame.
#include <optional>
#include <vector>

#include "eval/object_matching.h"
#include "geometry/pose.h"
#include "objects/object.h"

namespace slide::eval {

struct SharedLandmarks {
  std::vector<Eigen::Vector3d> in_a, in_b;  // the same real object, in frame a and in frame b
};

SharedLandmarks sharedLandmarks(const std::vector<Object>& map_a, const Pose& T_world_a, const std::vector<Object>& map_b,
                                const Pose& T_world_b, const std::vector<Object>& truth, const ObjectMatchOptions& mo);

// T_a_b with in_a ≈ T_a_b * in_b in the least-squares sense over the landmarks' horizontal
// positions (x, y and yaw; z of the result 0): heights of landmark centres are not comparable
// between robots (a trunk's centre is the middle of whatever part of it a robot saw). None below
// 3 shared landmarks.
std::optional<Pose> mapAlignment(const SharedLandmarks& shared);

// Horizontal distance |T_a_b * in_b - in_a| (x, y) per shared landmark.
std::vector<double> landmarkDistances(const SharedLandmarks& shared, const Pose& T_a_b);

// Horizontal translation (x, y) and yaw difference of `estimate` from `reference`.
struct HorizontalError {
  double translation_m = 0, yaw_deg = 0;
};
HorizontalError horizontalError(const Pose& estimate, const Pose& reference);

}  // namespace slide::eval
