#pragma once
// Plain-text point clouds: one point per line, "x y z" (further columns ignored; commas
// or spaces as separators; lines starting with '#' skipped).
#include <string>

#include "frontend/instance.h"

namespace slide::frontend {

// Throws IoError naming the file and line for a missing file or an unparsable line.
Cloud readXyzCloud(const std::string& path);

}  // namespace slide::frontend
