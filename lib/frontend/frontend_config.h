#pragma once
// All front-end parameters, loaded from config/frontend.yaml. Every key is optional (the
// defaults in the parameter structs apply); present keys of the wrong type or range are
// errors naming the file and key.
#include <string>

#include "frontend/geometric_segmenter.h"
#include "frontend/keypose.h"
#include "frontend/labelled_segmenter.h"
#include "frontend/rgbd_segmenter.h"
#include "frontend/shape_fit.h"
#include "frontend/tracker.h"

namespace slide {

struct FrontendConfig {
  std::string lidar_mode = "auto";  // auto (labelled when the scan has labels) | labelled | geometric
  LabelledSegmenterParams labelled;
  GeometricSegmenterParams geometric;
  RgbdSegmenterParams rgbd;
  FitParams fit;
  TrackerParams tracker;
  KeyposeParams keypose;
};

FrontendConfig loadFrontendConfig(const std::string& path);
// config/frontend.yaml of the source tree.
FrontendConfig loadDefaultFrontendConfig();

}  // namespace slide
