#pragma once
// PCD point clouds (ASCII, binary or binary_compressed), read with PCL and decoded by their
// fields as io/point_cloud2.h decodes PointCloud2 (x, y, z, intensity, ...). PCL's headers stay
// inside pcd_file.cpp.
#include <string>

#include "io/kitti_scan.h"

namespace slide::io {

// Throws IoError naming the file when it cannot be opened or parsed or lacks x, y or z.
// Non-finite points are skipped.
LabelledScan readPcdFile(const std::string& path);

}  // namespace slide::io
