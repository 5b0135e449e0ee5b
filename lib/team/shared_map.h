#pragma once
// A robot's object map as the team layer shares it for place recognition (key-pose bundles:
// objects/keypose_bundle.h).
#include <cstdint>
#include <vector>

#include "objects/object.h"

namespace slide::team {

struct SharedMap {
  std::int32_t robot = 0;        // who built it
  std::int32_t frame_robot = 0;  // whose frame it is expressed in
  std::int32_t version = 0;
  std::int64_t utime = 0;
  std::vector<Object> objects;
};

}  // namespace slide::team
