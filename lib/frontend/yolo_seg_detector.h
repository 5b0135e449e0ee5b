#pragma once
// A YOLOv8-seg instance segmentation network (the ultralytics ONNX export) run through OpenCV
// DNN as a MaskDetector, described by a YAML file (mask_detector_loader.h picks the kind):
//   type: yolov8-seg               # optional (the default)
//   model: yolov8n-seg.onnx        # relative to this YAML
//   input: {width: 640, height: 640}
//   swap_rb: true                  # the network takes RGB (ultralytics); frames are BGR
//   score_threshold: 0.25
//   nms_iou: 0.45
//   mask_threshold: 0.5
//   max_detections: 100
//   classes:                       # one per model class, in output order: its name and our
//     - {name: person, class: none}   # class (config/classes.yaml) or none (dropped)
//     - {name: chair, class: chair}
// Decoding: yolo_seg_decoder.h. Overlapping masks: the higher score keeps the pixel.
#include <memory>
#include <string>
#include <vector>

#include "frontend/rgbd_segmenter.h"
#include "frontend/yolo_seg_decoder.h"
#include "objects/class_table.h"

namespace slide::frontend {

struct YoloSegConfig {
  std::string file, model_path;
  YoloSegParams params;
  bool swap_rb = true;
  std::vector<std::string> model_classes;
  std::vector<int> class_of_model;  // our class id per model class, -1: dropped
};

// Throws ConfigError naming the file and key; a class name not in `classes` is an error.
YoloSegConfig loadYoloSegConfig(const std::string& path, const ClassTable& classes);

class YoloSegDetector : public MaskDetector {
 public:
  // Loads the network and runs it once on a blank input: a missing or unreadable file, or
  // outputs other than [1, 4 + classes + 32, anchors] and [1, 32, mh, mw], throw
  // std::runtime_error naming the file and the expectation.
  explicit YoloSegDetector(YoloSegConfig config);
  ~YoloSegDetector() override;
  std::string name() const override { return "yolov8-seg"; }
  // Fills frame.mask, instance_class, instance_confidence from frame.color (BGR). A frame
  // whose colour image does not match its intrinsics gets no instances.
  void detect(RgbdFrame& frame) const override;

 private:
  struct Net;
  YoloSegConfig config_;
  std::unique_ptr<Net> net_;
};

}  // namespace slide::frontend
