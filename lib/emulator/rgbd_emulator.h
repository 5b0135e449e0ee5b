#pragma once
// RGBD half of the detection emulator (parameters and behaviour: emulator/detection_emulator.h):
// YOLOv8-seg-class instance masks with confidences from a frame's ground-truth masks.
#include <vector>

#include <opencv2/core.hpp>

#include "io/rgbd_files.h"
#include "emulator/detection_emulator.h"

namespace slide::emulator {

struct EmulatedMasks {
  io::InstanceMask masks;              // CV_16UC1 ids 1..K, class per id, object ids 0
  std::vector<float> confidence;   // per id
};

// Emulated detections of a frame from its ground-truth instance mask and its depth image
// (CV_16UC1, depth_scale metres per unit). Throws std::invalid_argument when sizes differ.
EmulatedMasks emulateRgbdDetections(const io::InstanceMask& truth, const cv::Mat& depth, double depth_scale,
                                    const RgbdEmulatorParams& params, uint64_t seed);

}  // namespace slide::emulator
