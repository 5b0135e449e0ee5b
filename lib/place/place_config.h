#pragma once
// Place-recognition parameters (config/place.yaml), and one entry point for either method.
#include <string>

#include "place/slidegraph.h"
#include "place/slidematch.h"

namespace slide {

struct PlaceConfig {
  SlideGraphParams slidegraph;
  SlideMatchParams slidematch;
};

// Every key is optional (defaults of the structs above); a wrong type or value throws
// ConfigError naming the file and key. The shared `verify` section applies to both methods.
PlaceConfig loadPlaceConfig(const std::string& path);
// config/place.yaml of the source tree.
PlaceConfig loadDefaultPlaceConfig();

// "slidegraph" or "slidematch"; throws std::invalid_argument otherwise.
PlaceMethod parsePlaceMethod(const std::string& name);

PlaceResult recognizePlace(PlaceMethod method, const std::vector<Landmark>& a, const std::vector<Landmark>& b,
                           const PlaceConfig& config);

}  // namespace slide
