#pragma once
// The frames of one robot's recording, read one at a time by id: KITTI and TUM RGB-D folders,
// PCD folders, ROS 1 bags each implement it (io/robot_dataset.h picks one).
#include <cstddef>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "io/kitti_scan.h"
#include "io/rgbd_files.h"

namespace slide::io {

// One RGBD frame: colour 8-bit BGR, depth CV_16UC1 in the dataset's depth_scale units
// (0 = no depth), an instance mask when the recording has one.
struct RgbdImages {
  cv::Mat color, depth;
  std::optional<InstanceMask> mask;
};

class FrameReader {
 public:
  virtual ~FrameReader() = default;
  // LiDAR sweep `id` in the body frame. Throws IoError naming the file (and message) on bad data.
  virtual LabelledScan scan(std::size_t id) const = 0;
  // RGBD frame `id`. Throws IoError naming the file (and message) on bad data.
  virtual RgbdImages rgbd(std::size_t id) const = 0;
  // What reading has dropped so far (e.g. "1200 NaN points"); empty when nothing.
  virtual std::string dropSummary() const { return {}; }
};

}  // namespace slide::io
