#pragma once
// A range-image segmentation network (RangeNet++, SalsaNext or the project's own model, as an
// ONNX file described by a RangeModelConfig) run through OpenCV DNN as a PointLabeler: the scan
// is projected (range_image.h), normalised per channel, classified per pixel, and the classes'
// SemanticKITTI labels are back-projected to every point. Pixels whose winning class scores
// below min_confidence (softmax probability) label their points 0 (unlabelled).
#include <memory>
#include <optional>
#include <string>

#include "frontend/range_model_config.h"
#include "frontend/segmenter.h"

namespace slide::frontend {

// The front-end config's `segmenter.learned` section: which model, the confidence gate, and
// the robot's own sensor where it differs from the model's projection.
struct LearnedLidarParams {
  std::string model;            // model YAML (range_model_config.h); empty: no model configured
  double min_confidence = 0.0;  // softmax probability a pixel's class needs (0: off)
  std::optional<int> height, width;
  std::optional<double> fov_up_deg, fov_down_deg;
};

class RangeNetLabeler : public PointLabeler {
 public:
  // Loads and checks the model once with a blank image: a missing or unreadable ONNX file, a
  // model that refuses the configured input or gives an output other than
  // [1, classes, height, width] throws std::runtime_error naming the file and the expectation.
  RangeNetLabeler(RangeModelConfig config, double min_confidence = 0.0);
  ~RangeNetLabeler() override;
  std::string name() const override { return "learned"; }
  // Fills scan.semantic; clears scan.instance (the network separates no instances).
  void label(io::LabelledScan& scan) const override;
  const RangeModelConfig& config() const { return config_; }
  // The model of `params` with its overrides applied; throws std::runtime_error when no model
  // is configured, ConfigError / std::runtime_error as above for a bad one.
  static std::shared_ptr<const RangeNetLabeler> fromParams(const LearnedLidarParams& params);

 private:
  struct Net;  // the OpenCV DNN network, kept out of this header
  RangeModelConfig config_;
  double min_confidence_;
  std::unique_ptr<Net> net_;
};

}  // namespace slide::frontend
