#include "frontend/mask_detector_loader.h"

#include <filesystem>

#include "config/config.h"
#include "frontend/semantic_seg_detector.h"
#include "frontend/yolo_seg_detector.h"

namespace slide::frontend {

std::unique_ptr<MaskDetector> loadMaskDetector(const std::string& path, const ClassTable& classes) {
  if (detectorTypeOf(ConfigNode::load(path)) == "semantic")
    return std::make_unique<SemanticSegDetector>(loadSemanticSegConfig(path, classes));
  return std::make_unique<YoloSegDetector>(loadYoloSegConfig(path, classes));
}

std::string detectorTypeOf(const ConfigNode& root) {
  const std::string type = root.get<std::string>("type", "yolov8-seg");
  if (type != "yolov8-seg" && type != "semantic") root.fail("type", "expected yolov8-seg or semantic, not '" + type + "'");
  return type;
}

ConfigNode loadModelYaml(const std::string& path, const std::string& type) {
  ConfigNode root = ConfigNode::load(path);
  const std::string is = detectorTypeOf(root);
  if (is != type) root.fail("type", "this YAML is read as a " + type + " model, not " + is);
  return root;
}

std::string modelPathOf(const ConfigNode& root) {
  const std::filesystem::path model = root.get<std::string>("model");
  return model.is_absolute() ? model.string() : (std::filesystem::path(root.file()).parent_path() / model).string();
}

void readInputSize(const ConfigNode& root, int min_side, int& width, int& height) {
  const ConfigNode input = root.child("input");
  input.read("width", width);
  input.read("height", height);
  const std::string range = "must be " + std::to_string(min_side) + "..4096";
  if (width < min_side || width > 4096) input.fail("width", range);
  if (height < min_side || height > 4096) input.fail("height", range);
}

void readModelClasses(const ConfigNode& root, const ClassTable& classes, std::vector<std::string>& names,
                      std::vector<int>& class_of_model) {
  const ConfigNode list = root.child("classes");
  if (list.size() < 1 || list.size() > 1000) root.fail("classes", "expected a list of 1..1000 classes");
  names.clear(), class_of_model.clear();
  for (std::size_t k = 0; k < list.size(); ++k) {
    const ConfigNode e = list[k];
    names.push_back(e.get<std::string>("name"));
    const std::string ours = e.get<std::string>("class");
    const ClassInfo* info = ours == "none" ? nullptr : classes.findByName(ours);
    if (ours != "none" && !info) e.fail("class", "no class named '" + ours + "' in the class table (or none)");
    class_of_model.push_back(info ? info->id : -1);
  }
}

}  // namespace slide::frontend
