#pragma once
// RGBD instances: each instance mask's depth is median-filtered within the mask
// (depth_filter.h), then the mask is backprojected with the depth image, keeping only
// pixels whose depth lies in a percentile band around the mask's median depth (drops the
// background and mixed edge pixels), after a detector-confidence gate. Pixels at the mask's
// edge are judged by their own depth against that band. A learned detector (YOLOv8-seg, or a
// per-pixel semantic model split by depth; mask_detector_loader.h) plugs in as a MaskDetector
// that fills the masks from the colour image.
#include <cstdint>
#include <string>
#include <vector>

#include "frontend/input_issues.h"
#include "frontend/instance.h"
#include "objects/class_table.h"

namespace slide::frontend {

struct CameraIntrinsics {
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  double depth_scale = 0.001;  // metres per raw depth unit
};

struct RgbdFrame {
  CameraIntrinsics intrinsics;
  std::vector<std::uint8_t> color;    // BGR, width*height*3 (may be empty)
  std::vector<std::uint16_t> depth;   // width*height raw units, 0 = missing
  std::vector<std::uint16_t> mask;    // width*height instance ids (index + 1), 0 = none
  std::vector<int> instance_class;    // per instance
  std::vector<float> instance_confidence;
};

// A learned image detector: fills frame.mask, instance_class and instance_confidence from
// frame.color (and frame.depth, which a semantic model's instances are split by).
class MaskDetector {
 public:
  virtual ~MaskDetector() = default;
  virtual std::string name() const = 0;
  virtual void detect(RgbdFrame& frame) const = 0;
};

// What a MaskDetector's detect does first: empties the instances (classes, confidences, the
// mask all 0 at the intrinsics' size), and says whether the frame has a colour image of that
// size to detect on.
bool resetDetections(RgbdFrame& frame);

struct RgbdSegmenterParams {
  double min_confidence = 0.25;
  double band_fraction = 0.8;  // keep depths between the (0.5 -+ band/2) quantiles of the mask
  double band_margin = 0.05;   // metres added on both sides of the band
  double min_depth = 0.2, max_depth = 12.0;  // metres
  int median_radius = 2;       // depth median window (pixels) within each mask, 0 = off
  int stride = 1;              // pixel step (1 = every pixel)
  int erode_px = 0;            // mask pixels this close to another id are edge pixels: a detector's masks spill
                               // a few pixels over the object's edge onto the background; they take no part in
                               // the depth band ...
  bool restore_edges = true;   // ... and are kept only when their own unfiltered depth lies in the band (false: dropped)
  int min_points = 30;
};

// Instances of one frame in the camera's body frame (x forward, y left, z up: the optical
// frame z-forward is rotated accordingly). Frames whose images do not match the intrinsics
// give no instances and count an issue; unknown classes and missing depth are counted.
std::vector<Instance> segmentRgbd(const RgbdFrame& frame, const ClassTable& classes, const RgbdSegmenterParams& params,
                                  InputIssues& issues);

}  // namespace slide::frontend
