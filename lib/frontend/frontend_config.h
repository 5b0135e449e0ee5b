#pragma once
// All front-end parameters, loaded from config/frontend.yaml. Every key is optional (the
// defaults in the parameter structs apply); present keys of the wrong type or range are
// errors naming the file and key.
#include <string>

#include "frontend/geometric_segmenter.h"
#include "frontend/keypose.h"
#include "frontend/labelled_segmenter.h"
#include "frontend/range_net_labeler.h"
#include "frontend/rgbd_segmenter.h"
#include "frontend/shape_fit.h"
#include "frontend/tracker.h"

namespace slide::frontend {

struct FrontendConfig {
  // auto (labelled when the scan has labels) | labelled | geometric | learned (a range-image
  // model labels the points, the labelled segmenter clusters them)
  std::string lidar_mode = "auto";
  LabelledSegmenterParams labelled;
  LearnedLidarParams learned;  // model path resolved against the config file's folder
  GeometricSegmenterParams geometric;
  RgbdSegmenterParams rgbd;
  std::string rgbd_detector;  // model YAML (mask_detector_loader.h: YOLOv8-seg or per-pixel semantic); empty: the frames' own masks
  FitParams fit;
  TrackerParams tracker;
  KeyPoseParams keypose;
};

FrontendConfig loadFrontendConfig(const std::string& path);
// config/frontend.yaml of the source tree.
FrontendConfig loadDefaultFrontendConfig();

}  // namespace slide::frontend
