#pragma once
// Loop-closer parameters from YAML (config/loop_closer.yaml): scheduling, consensus, method,
// and the place-recognition parameters (a `place` section with config/place.yaml's layout,
// or the file named by `place_config`).
#include <string>

#include "place/loop_closer.h"

namespace slide {

// Every key is optional; errors name the file and key (ConfigError).
LoopCloserParams loadLoopCloserParams(const std::string& path);

}  // namespace slide
