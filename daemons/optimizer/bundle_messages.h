#pragma once
// Conversions between the optimizer's LCM messages and lib/backend types.
#include <string>
#include <vector>

#include "backend/keypose_bundle.h"
#include "backend/optimizer.h"
#include "slide/keypose_bundle_t.hpp"
#include "slide/object_map_t.hpp"
#include "slide/trajectory_t.hpp"

namespace slide {

// Malformed objects (not exactly one model) are left out and described in `warnings`.
KeyPoseBundle fromMsg(const keypose_bundle_t& m, std::vector<std::string>& warnings);
keypose_bundle_t toMsg(const KeyPoseBundle& b);

object_map_t objectMapMsg(std::int64_t utime, int robot, const std::vector<Object>& objects);
trajectory_t trajectoryMsg(std::int64_t utime, int robot, int frame_robot, const std::vector<TrajectoryPose>& poses);

}  // namespace slide
