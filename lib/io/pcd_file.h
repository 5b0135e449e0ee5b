#pragma once
// PCD point clouds (ASCII, binary or binary_compressed), read with PCL: fields x, y, z and,
// when present, intensity. PCL's headers stay inside pcd_file.cpp.
#include <string>

#include "io/kitti_scan.h"

namespace slide {

// Throws IoError naming the file when it cannot be opened or parsed or lacks x, y or z.
// Points are kept as stored (non-finite ones too: the segmenters count and skip them).
LabelledScan readPcdFile(const std::string& path);

}  // namespace slide
