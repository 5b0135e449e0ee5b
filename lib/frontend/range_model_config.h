#pragma once
// What a range-image segmentation model (RangeNet++, SalsaNext, the project's own
// config/models/slide_range_net) expects and gives, read from the model's YAML file:
//   model: slide_range_net.onnx          # ONNX file, relative to this YAML
//   projection: {height: 64, width: 1024, fov_up_deg: 3.0, fov_down_deg: -25.0}
//   channels: [range, x, y, z, remission] # input channels in the model's order
//   means: [...]                         # per channel, the training set's statistics
//   stds: [...]
//   scores: logits                       # output: logits | probabilities (per pixel)
//   classes:                             # one per output channel, in order: the model's name
//     - {name: car, label: 10}           # and the SemanticKITTI label its points get (0: none)
// Input blob [1, channels, height, width]; output [1, classes, height, width].
#include <cstdint>
#include <string>
#include <vector>

#include "frontend/range_image.h"

namespace slide {
class ConfigNode;
}  // namespace slide

namespace slide::frontend {

struct RangeModelClass {
  std::string name;
  uint16_t label = 0;  // SemanticKITTI class id written to the points (0: unlabelled)
};

struct RangeModelConfig {
  std::string file;        // the YAML it was read from
  std::string model_path;  // the ONNX file, resolved against the YAML's folder
  RangeProjection projection;
  std::vector<RangeChannel> channels;
  std::vector<float> means, stds;
  bool logits = true;      // false: the model gives probabilities already
  std::vector<RangeModelClass> classes;
};

// Throws ConfigError naming the file and key for a missing file, a missing or malformed key,
// a zero std, or lists of unequal length.
RangeModelConfig loadRangeModelConfig(const std::string& path);
// Reads the projection keys present in `n` (height, width, fov_up_deg, fov_down_deg,
// search_rows, search_cols) into `p`; ConfigError for values out of range.
void readRangeProjection(const ConfigNode& n, RangeProjection& p);

}  // namespace slide::frontend
