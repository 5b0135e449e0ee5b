#pragma once
// KITTI velodyne scans (float32 x, y, z, intensity per point) and SemanticKITTI labels
// (uint32 per point: lower 16 bits class, upper 16 bits instance).
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace slide::io {

struct LabelledScan {
  std::vector<Eigen::Vector3f> xyz;
  std::vector<float> intensity;
  std::vector<uint16_t> semantic;  // empty when unlabelled
  std::vector<uint16_t> instance;  // empty when unlabelled
  bool hasLabels() const { return !semantic.empty(); }
  std::size_t size() const { return xyz.size(); }
};

LabelledScan readVelodyneBin(const std::string& path);
// Reads labels into `scan`; throws IoError when the count does not match the points.
void readLabels(const std::string& path, LabelledScan& scan);
// Scan plus labels at the matching path (velodyne/NNNNNN.bin -> labels/NNNNNN.label), if present.
LabelledScan readLabelledScan(const std::string& bin_path);

void writeVelodyneBin(const std::string& path, const LabelledScan& scan);
void writeLabels(const std::string& path, const LabelledScan& scan);

}  // namespace slide::io
