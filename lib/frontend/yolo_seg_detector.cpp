#include "frontend/yolo_seg_detector.h"

#include <opencv2/dnn.hpp>
#include <stdexcept>

#include "config/config.h"
#include "frontend/mask_detector_loader.h"
#include "frontend/onnx_file.h"

namespace slide::frontend {

YoloSegConfig loadYoloSegConfig(const std::string& path, const ClassTable& classes) {
  const ConfigNode root = loadModelYaml(path, "yolov8-seg");
  YoloSegConfig c;
  c.file = path, c.model_path = modelPathOf(root);
  YoloSegParams& p = c.params;
  readInputSize(root, 32, p.input_width, p.input_height);
  root.read("swap_rb", c.swap_rb);
  root.read("score_threshold", p.score_threshold);
  root.read("nms_iou", p.nms_iou);
  root.read("mask_threshold", p.mask_threshold);
  root.read("max_detections", p.max_detections);
  if (!(p.score_threshold >= 0 && p.score_threshold <= 1)) root.fail("score_threshold", "must be 0..1");
  if (!(p.nms_iou >= 0 && p.nms_iou <= 1)) root.fail("nms_iou", "must be 0..1");
  if (!(p.mask_threshold >= 0 && p.mask_threshold <= 1)) root.fail("mask_threshold", "must be 0..1");
  if (p.max_detections < 1 || p.max_detections > 1000) root.fail("max_detections", "must be 1..1000");
  readModelClasses(root, classes, c.model_classes, c.class_of_model);
  root.rejectUnknownKeys();
  return c;
}

struct YoloSegDetector::Net {
  cv::dnn::Net net;
  std::vector<std::string> outputs;
};

namespace {
// output0 and output1 of one forward pass; exceptions name the file.
std::pair<cv::Mat, cv::Mat> run(cv::dnn::Net& net, const std::vector<std::string>& names, const cv::Mat& input_bgr,
                                const YoloSegConfig& c) {
  std::vector<cv::Mat> outs;
  try {
    net.setInput(cv::dnn::blobFromImage(input_bgr, 1.0 / 255.0, cv::Size(), cv::Scalar(), c.swap_rb, false));
    net.forward(outs, names);
  } catch (const cv::Exception& e) {
    throw std::runtime_error(c.model_path + ": the model does not run on an input of [1, 3, " +
                             std::to_string(c.params.input_height) + ", " + std::to_string(c.params.input_width) + "] (" +
                             c.file + "): " + e.what());
  }
  if (outs.size() != 2)
    throw std::runtime_error(c.model_path + ": " + std::to_string(outs.size()) +
                             " outputs, expected 2 (YOLOv8-seg: detections and mask prototypes)");
  if (outs[0].dims == 4 && outs[1].dims == 3) std::swap(outs[0], outs[1]);
  return {outs[0], outs[1]};
}
}  // namespace

YoloSegDetector::YoloSegDetector(YoloSegConfig config) : config_(std::move(config)), net_(std::make_unique<Net>()) {
  const std::string& path = config_.model_path;
  net_->net = readOnnxFile(path, config_.file, [](const std::string& p) { return cv::dnn::readNetFromONNX(p); });
  net_->outputs = net_->net.getUnconnectedOutLayersNames();
  const YoloSegParams& p = config_.params;
  const cv::Mat blank(p.input_height, p.input_width, CV_8UC3, cv::Scalar(114, 114, 114));
  const auto [out0, out1] = run(net_->net, net_->outputs, blank, config_);
  try {
    decodeYoloSeg(out0, out1, static_cast<int>(config_.class_of_model.size()), letterboxOf(p.input_width, p.input_height, p.input_width, p.input_height),
                  p.input_width, p.input_height, p);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + ": " + e.what() + " (" + std::to_string(config_.class_of_model.size()) + " classes in " +
                             config_.file + ")");
  }
}

YoloSegDetector::~YoloSegDetector() = default;

void YoloSegDetector::detect(RgbdFrame& f) const {
  if (!resetDetections(f)) return;
  const int w = f.intrinsics.width, h = f.intrinsics.height;
  const YoloSegParams& p = config_.params;
  const cv::Mat bgr(h, w, CV_8UC3, f.color.data());
  const Letterbox lb = letterboxOf(w, h, p.input_width, p.input_height);
  const auto [out0, out1] = run(net_->net, net_->outputs, letterboxImage(bgr, lb, p.input_width, p.input_height), config_);
  paintInstances(decodeYoloSeg(out0, out1, static_cast<int>(config_.class_of_model.size()), lb, w, h, p),
                 config_.class_of_model, f);
}

}  // namespace slide::frontend
