#pragma once
// Loop-closer parameters from YAML (config/loop_closer.yaml): scheduling, consensus, method,
// and the place-recognition parameters (a `place` section with config/place.yaml's layout,
// or the file named by `place_config`).
#include <string>

#include "place/loop_closer.h"

namespace slide {
class ConfigNode;
}  // namespace slide

namespace slide::place {

// Every key is optional; errors name the file and key (ConfigError). Reads the loop closer's
// keys of `root` (a relative place_config is taken relative to root's file); the daemon reads
// its bus keys from the same file and then rejects the keys neither knows.
LoopCloserParams loadLoopCloserParams(const ConfigNode& root);

}  // namespace slide::place
