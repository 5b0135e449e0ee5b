#pragma once
// Place-recognition parameters (config/place.yaml), and one entry point for either method.
#include <string>

#include "place/slidegraph.h"
#include "place/slidematch.h"

namespace slide {

struct PlaceConfig {
  SlideGraphParams slidegraph;
  SlideMatchParams slidematch;
  // Two maps whose classes overlap less than this (sharedClassShare: e.g. a label-free LiDAR's
  // "other" furniture against an RGBD detector's chairs and tables) are matched by shape family.
  double min_shared_class_share = 0.5;
};

// Every key is optional (defaults of the structs above); a wrong type or value throws
// ConfigError naming the file and key. The shared `verify` section applies to both methods.
PlaceConfig loadPlaceConfig(const std::string& path);
// config/place.yaml of the source tree.
PlaceConfig loadDefaultPlaceConfig();

// "slidegraph" or "slidematch"; throws std::invalid_argument otherwise.
PlaceMethod parsePlaceMethod(const std::string& name);

// Matches with the configured method; by shape family when the maps' classes barely overlap
// (the result's reason or log line says so through `by_shape`).
PlaceResult recognizePlace(PlaceMethod method, const std::vector<Landmark>& a, const std::vector<Landmark>& b,
                           const PlaceConfig& config);

}  // namespace slide
