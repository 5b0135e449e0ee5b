#pragma once
// The MaskDetector a model YAML describes (the file segmenter.rgbd.detector names), chosen by
// its `type:` key:
//   yolov8-seg (also when the key is absent) -> YoloSegDetector (yolo_seg_detector.h)
//   semantic                                 -> SemanticSegDetector (semantic_seg_detector.h)
// and the reading of the keys both kinds of YAML share (type, model, classes).
#include <memory>
#include <string>
#include <vector>

#include "frontend/rgbd_segmenter.h"
#include "objects/class_table.h"

namespace slide {
class ConfigNode;
}  // namespace slide

namespace slide::frontend {

// Throws ConfigError naming the file and key for a bad YAML (an unknown type among them), and
// std::runtime_error naming the model file for a missing, corrupt or wrongly shaped model.
std::unique_ptr<MaskDetector> loadMaskDetector(const std::string& path, const ClassTable& classes);

// The YAML's `type` (yolov8-seg when absent); ConfigError unless it is one of the two.
std::string detectorTypeOf(const ConfigNode& root);
// The model YAML at `path`; ConfigError (naming the file) for a missing or unparsable file, and
// at `type` unless its type is `type`.
ConfigNode loadModelYaml(const std::string& path, const std::string& type);
// The `model` key resolved against the YAML's folder (an absolute path is kept).
std::string modelPathOf(const ConfigNode& root);
// The required `input` map's width and height (each kept when absent), each min_side..4096.
void readInputSize(const ConfigNode& root, int min_side, int& width, int& height);
// The `classes` list: 1..1000 entries {name: <the model's>, class: <ours> | none}, into the
// model's class names (output order) and our class id per model class (-1: none, dropped); a
// class name not in `classes` is a ConfigError.
void readModelClasses(const ConfigNode& root, const ClassTable& classes, std::vector<std::string>& names,
                      std::vector<int>& class_of_model);

}  // namespace slide::frontend
