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

namespace slide {

struct SharedLandmarks {
  std::vector<Eigen::Vector3d> in_a, in_b;  // the same real object, in frame a and in frame b
};

SharedLandmarks sharedLandmarks(const std::vector<Object>& map_a, const Pose& T_world_a, const std::vector<Object>& map_b,
                                const Pose& T_world_b, const std::vector<Object>& truth, const ObjectMatchOptions& mo);

// T_a_b with in_a ≈ T_a_b * in_b in the least-squares sense; none below 3 shared landmarks.
std::optional<Pose> mapAlignment(const SharedLandmarks& shared);

// |T_a_b * in_b - in_a| per shared landmark.
std::vector<double> landmarkDistances(const SharedLandmarks& shared, const Pose& T_a_b);

}  // namespace slide
