#pragma once
// The optimizer's output messages from lib/backend types (its key-pose bundles: msg/convert.h).
#include <string>
#include <vector>

#include "backend/optimizer.h"
#include "msg/convert.h"
#include "slide/object_map_t.hpp"
#include "slide/trajectory_t.hpp"

namespace slide {

object_map_t objectMapMsg(std::int64_t utime, int robot, const std::vector<Object>& objects);
trajectory_t trajectoryMsg(std::int64_t utime, int robot, int frame_robot,
                           const std::vector<backend::TrajectoryPose>& poses);

}  // namespace slide
