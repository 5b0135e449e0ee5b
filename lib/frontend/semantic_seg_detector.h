#pragma once
// A per-pixel semantic segmentation network (any ONNX model with one output of scores
// [1, classes, h, w]) run through OpenCV DNN as a MaskDetector: instances are the
// depth-aware connected components of its per-pixel classes (semantic_seg_decoder.h).
// Described by a YAML file (mask_detector_loader.h picks the kind by `type`):
//   type: semantic
//   model: my_segmenter.onnx       # relative to this YAML
//   input: {width: 640, height: 480}   # the colour image is resized (stretched) to it
//   swap_rb: true                  # the network takes RGB; frames are BGR
//   mean: [123.675, 116.28, 103.53]    # per network input channel, in 0..255 pixel units:
//   std: [58.395, 57.12, 57.375]       #   input = (pixel - mean) / std
//   scores: logits                 # logits (softmax applied) | probabilities
//   min_confidence: 0.5            # pixels whose best class is less probable stay unlabelled
//   components:                    # neighbours (4-connected) of one class join when their
//     depth_step_m: 0.10           #   depths differ by at most max(depth_step_m,
//     depth_step_fraction: 0.05    #   depth_step_fraction * the nearer depth)
//     min_pixels: 50               # smaller components are dropped
//   classes:                       # one per output channel, in order: its name and our
//     - {name: wall, class: none}  # class (config/classes.yaml) or none (dropped)
//     - {name: chair, class: chair}
// Every key but model, input and classes is optional (the values above are the defaults but
// for mean and std: 0 and 255, inputs in 0..1).
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "frontend/rgbd_segmenter.h"
#include "frontend/semantic_seg_decoder.h"
#include "objects/class_table.h"

namespace slide::frontend {

struct SemanticSegConfig {
  std::string file, model_path;
  int input_width = 640, input_height = 480;
  bool swap_rb = true;
  std::array<double, 3> mean{0, 0, 0}, stddev{255, 255, 255};  // network channel order (keys mean, std)
  SemanticSegParams params;
  std::vector<std::string> model_classes;
  std::vector<int> class_of_model;  // our class id per model class, -1: dropped
};

// Throws ConfigError naming the file and key (a class name not in `classes`, a zero std, a
// type other than semantic among them).
SemanticSegConfig loadSemanticSegConfig(const std::string& path, const ClassTable& classes);

// The network input [1, 3, input_height, input_width] (float, network channel order) of a BGR
// image: resized to the input (bilinear), channels swapped when swap_rb, normalised.
std::vector<float> semanticSegInput(const cv::Mat& bgr, const SemanticSegConfig& config);

class SemanticSegDetector : public MaskDetector {
 public:
  // Loads the network and runs it once on a blank input: a missing or unreadable file, or an
  // output other than [1, classes, input_height / f, input_width / f] (f = 1, 2, 3, ...)
  // throws std::runtime_error naming the file and the expectation.
  explicit SemanticSegDetector(SemanticSegConfig config);
  ~SemanticSegDetector() override;
  std::string name() const override { return "semantic"; }
  // Fills frame.mask, instance_class, instance_confidence from frame.color (BGR) and
  // frame.depth. A frame whose colour or depth image does not match its intrinsics gets no
  // instances.
  void detect(RgbdFrame& frame) const override;

 private:
  struct Net;  // the OpenCV DNN network, kept out of this header
  SemanticSegConfig config_;
  std::unique_ptr<Net> net_;
};

}  // namespace slide::frontend
