#pragma once
// A file argument with an optional placement: "PATH" or "PATH@x,y,z,yaw" (metres, degrees),
// so that maps and trajectories of several robots can be shown or scored in one frame.
#include <string>

#include "geometry/pose.h"

namespace slide::eval {

struct PlacedFile {
  std::string path;
  Pose placement = Pose::Identity();  // maps the file's frame into the common frame
};

// Throws std::invalid_argument naming the argument when the placement is not 4 numbers.
PlacedFile parsePlacedFile(const std::string& arg);

}  // namespace slide::eval
