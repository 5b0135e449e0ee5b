#pragma once
// TUM trajectory files: "timestamp tx ty tz qx qy qz qw" per line, '#' comments.
#include <string>
#include <vector>

#include "geometry/stamped_pose.h"

namespace slide::io {

std::vector<StampedPose> readTum(const std::string& path);
// Written whole or not at all (io/atomic_file.h); throws IoError.
void writeTum(const std::string& path, const std::vector<StampedPose>& trajectory);

}  // namespace slide::io
