#include "frontend/semantic_seg_detector.h"

#include <algorithm>
#include <cmath>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "config/config.h"
#include "frontend/mask_detector_loader.h"
#include "frontend/mat_shape.h"
#include "frontend/onnx_file.h"

namespace slide::frontend {

SemanticSegConfig loadSemanticSegConfig(const std::string& path, const ClassTable& classes) {
  const ConfigNode root = loadModelYaml(path, "semantic");
  SemanticSegConfig c;
  c.file = path, c.model_path = modelPathOf(root);
  readInputSize(root, 1, c.input_width, c.input_height);
  root.read("swap_rb", c.swap_rb);
  if (root.has("mean")) {
    const auto v = root.getList<double>("mean", 3);
    for (double m : v)
      if (!std::isfinite(m)) root.fail("mean", "must be three finite numbers");
    std::copy(v.begin(), v.end(), c.mean.begin());
  }
  if (root.has("std")) {
    const auto v = root.getList<double>("std", 3);
    for (double s : v)
      if (!(s > 0) || !std::isfinite(s)) root.fail("std", "must be three positive numbers");
    std::copy(v.begin(), v.end(), c.stddev.begin());
  }
  SemanticSegParams& p = c.params;
  const std::string scores = root.get<std::string>("scores", "logits");
  if (scores != "logits" && scores != "probabilities") root.fail("scores", "expected logits or probabilities");
  p.logits = scores == "logits";
  root.read("min_confidence", p.min_confidence);
  if (!(p.min_confidence >= 0 && p.min_confidence <= 1)) root.fail("min_confidence", "must be 0..1");
  if (root.has("components")) {
    const ConfigNode cc = root.child("components");
    cc.read("depth_step_m", p.depth_step_m);
    cc.read("depth_step_fraction", p.depth_step_fraction);
    cc.read("min_pixels", p.min_pixels);
    cc.requireNonNegative("depth_step_m", p.depth_step_m);
    if (!(p.depth_step_fraction >= 0 && p.depth_step_fraction <= 1)) cc.fail("depth_step_fraction", "must be 0..1");
    if (p.min_pixels < 1) cc.fail("min_pixels", "must be at least 1");
  }
  readModelClasses(root, classes, c.model_classes, c.class_of_model);
  root.rejectUnknownKeys();
  return c;
}

std::vector<float> semanticSegInput(const cv::Mat& bgr, const SemanticSegConfig& c) {
  if (bgr.type() != CV_8UC3 || bgr.empty()) throw std::invalid_argument("semantic segmentation input: expected a BGR 8-bit image");
  const int w = c.input_width, h = c.input_height;
  cv::Mat img = bgr;
  if (bgr.cols != w || bgr.rows != h) cv::resize(bgr, img, cv::Size(w, h), 0, 0, cv::INTER_LINEAR);
  const std::size_t plane = static_cast<std::size_t>(w) * h;
  std::vector<float> blob(3 * plane);
  for (int k = 0; k < 3; ++k) {  // network channel k
    const int channel = c.swap_rb ? 2 - k : k;
    const float mean = static_cast<float>(c.mean[k]), inv_std = static_cast<float>(1.0 / c.stddev[k]);
    float* out = blob.data() + k * plane;
    for (int v = 0; v < h; ++v) {
      const std::uint8_t* row = img.ptr<std::uint8_t>(v);
      for (int u = 0; u < w; ++u) out[static_cast<std::size_t>(v) * w + u] = (row[3 * u + channel] - mean) * inv_std;
    }
  }
  return blob;
}

struct SemanticSegDetector::Net {
  cv::dnn::Net net;
};

namespace {
// The scores of one forward pass, checked against the config; exceptions name the file.
cv::Mat forward(cv::dnn::Net& net, std::vector<float>& blob, const SemanticSegConfig& c) {
  const int dims[4] = {1, 3, c.input_height, c.input_width};
  cv::Mat out;
  try {
    net.setInput(cv::Mat(4, dims, CV_32F, blob.data()));
    out = net.forward();
  } catch (const cv::Exception& e) {
    throw std::runtime_error(c.model_path + ": the model does not run on an input of [1, 3, " +
                             std::to_string(c.input_height) + ", " + std::to_string(c.input_width) + "] (" + c.file +
                             "): " + e.what());
  }
  const int k = static_cast<int>(c.class_of_model.size());
  const bool ok = out.type() == CV_32F && out.dims == 4 && out.size[0] == 1 && out.size[1] == k && out.size[2] >= 1 &&
                  out.size[3] >= 1 && c.input_height % out.size[2] == 0 && c.input_width % out.size[3] == 0 &&
                  c.input_height / out.size[2] == c.input_width / out.size[3];
  if (!ok)
    throw std::runtime_error(c.model_path + ": output " + shapeText(out) + ", expected float [1, " + std::to_string(k) +
                             " classes (" + c.file + "), " + std::to_string(c.input_height) + ", " +
                             std::to_string(c.input_width) + "] or the input size divided by a whole factor");
  return out;
}
}  // namespace

SemanticSegDetector::SemanticSegDetector(SemanticSegConfig config) : config_(std::move(config)), net_(std::make_unique<Net>()) {
  net_->net = readOnnxFile(config_.model_path, config_.file, [](const std::string& p) { return cv::dnn::readNetFromONNX(p); });
  const cv::Mat blank(config_.input_height, config_.input_width, CV_8UC3, cv::Scalar(114, 114, 114));
  std::vector<float> blob = semanticSegInput(blank, config_);
  forward(net_->net, blob, config_);
}

SemanticSegDetector::~SemanticSegDetector() = default;

void SemanticSegDetector::detect(RgbdFrame& f) const {
  if (!resetDetections(f) || f.depth.size() != f.mask.size()) return;
  const int w = f.intrinsics.width, h = f.intrinsics.height;
  std::vector<float> blob = semanticSegInput(cv::Mat(h, w, CV_8UC3, f.color.data()), config_);
  const cv::Mat scores = forward(net_->net, blob, config_);
  const int k = static_cast<int>(config_.class_of_model.size());
  const PixelClasses pixels = classifyPixels(scores, k, w, h, config_.params);
  paintSemanticInstances(depthComponents(pixels, f.depth, f.intrinsics.depth_scale, config_.params),
                         config_.class_of_model, f);
}

}  // namespace slide::frontend
