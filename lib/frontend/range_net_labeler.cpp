#include "frontend/range_net_labeler.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <opencv2/dnn.hpp>
#include <stdexcept>

#include "frontend/mat_shape.h"
#include "frontend/onnx_file.h"

namespace slide::frontend {

struct RangeNetLabeler::Net {
  cv::dnn::Net net;
};

namespace {
// Runs the network on `blob` (1 x C x H x W) and returns its output; exceptions name the file.
cv::Mat forward(cv::dnn::Net& net, std::vector<float>& blob, const RangeModelConfig& c) {
  const int dims[4] = {1, static_cast<int>(c.channels.size()), c.projection.height, c.projection.width};
  const std::string expected = "[1, " + std::to_string(dims[1]) + ", " + std::to_string(dims[2]) + ", " +
                               std::to_string(dims[3]) + "]";
  cv::Mat out;
  try {
    net.setInput(cv::Mat(4, dims, CV_32F, blob.data()));
    out = net.forward();
  } catch (const cv::Exception& e) {
    throw std::runtime_error(c.model_path + ": the model does not run on an input of " + expected + " (" + c.file +
                             "): " + e.what());
  }
  const int k = static_cast<int>(c.classes.size());
  if (out.dims != 4 || out.size[0] != 1 || out.size[1] != k || out.size[2] != dims[2] || out.size[3] != dims[3] ||
      out.type() != CV_32F)
    throw std::runtime_error(c.model_path + ": output " + shapeText(out) + ", expected float [1, " + std::to_string(k) +
                             " classes (" + c.file + "), " + std::to_string(dims[2]) + ", " + std::to_string(dims[3]) + "]");
  return out;
}
}  // namespace

RangeNetLabeler::RangeNetLabeler(RangeModelConfig config, double min_confidence)
    : config_(std::move(config)), min_confidence_(min_confidence), net_(std::make_unique<Net>()) {
  net_->net = readOnnxFile(config_.model_path, config_.file, [](const std::string& p) { return cv::dnn::readNetFromONNX(p); });
  net_->net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net_->net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  std::vector<float> blank(config_.channels.size() * config_.projection.height * config_.projection.width, 0.0f);
  forward(net_->net, blank, config_);
}

RangeNetLabeler::~RangeNetLabeler() = default;

std::shared_ptr<const RangeNetLabeler> RangeNetLabeler::fromParams(const LearnedLidarParams& params) {
  if (params.model.empty()) throw std::runtime_error("lidar mode learned: no model configured (segmenter.learned.model)");
  RangeModelConfig c = loadRangeModelConfig(params.model);
  RangeProjection& p = c.projection;
  p.height = params.height.value_or(p.height);
  p.width = params.width.value_or(p.width);
  p.fov_up_deg = params.fov_up_deg.value_or(p.fov_up_deg);
  p.fov_down_deg = params.fov_down_deg.value_or(p.fov_down_deg);
  if (!(p.fov_up_deg > p.fov_down_deg)) throw std::runtime_error(params.model + ": fov_up_deg must exceed fov_down_deg after the front-end config's overrides");
  return std::make_shared<const RangeNetLabeler>(std::move(c), params.min_confidence);
}

void RangeNetLabeler::label(io::LabelledScan& scan) const {
  const RangeProjection& p = config_.projection;
  const RangeImage img = projectScan(scan, p);
  std::vector<float> blob = rangeImageInput(scan, img, config_.channels, config_.means, config_.stds);
  const cv::Mat out = forward(net_->net, blob, config_);
  const int k = static_cast<int>(config_.classes.size());
  const std::size_t pixels = static_cast<std::size_t>(p.height) * p.width;
  const float* scores = out.ptr<float>();
  std::vector<uint16_t> pixel_labels(pixels, 0);
  // Softmax gate on logits without an exp per class where the two best scores decide it: the
  // winner's probability is 1 / sum_c exp(s_c - top), at most 1 / (1 + exp(second - top)) and
  // at least 1 / (1 + (k - 1) exp(second - top)).
  const double odds = min_confidence_ > 0 && min_confidence_ < 1 ? 1.0 / min_confidence_ - 1.0 : 0.0;
  const float inf = std::numeric_limits<float>::infinity();
  const float fail_gap = odds > 0 ? static_cast<float>(std::log(1.0 / odds)) : -inf;  // odds 0: never decided early
  const float sure_gap = odds > 0 ? static_cast<float>(std::log(std::max(1, k - 1) / odds)) : inf;
  for (std::size_t px = 0; px < pixels; ++px) {
    if (img.point_of_pixel[px] < 0) continue;
    int best = 0;
    float top = scores[px], second = -inf;
    for (int c = 1; c < k; ++c) {
      const float s = scores[c * pixels + px];
      if (s > top) second = top, top = s, best = c;
      else if (s > second) second = s;
    }
    if (min_confidence_ > 0) {
      if (!config_.logits) {
        if (top < min_confidence_) continue;
      } else if (top - second < fail_gap) {  // probability below 1 / (1 + odds) = min_confidence
        continue;
      } else if (top - second < sure_gap) {  // undecided: the whole softmax
        double sum = 0;
        for (int c = 0; c < k; ++c) sum += std::exp(double(scores[c * pixels + px]) - top);
        if (1.0 / sum < min_confidence_) continue;
      }
    }
    pixel_labels[px] = config_.classes[best].label;
  }
  scan.semantic = backProjectLabels(scan, img, pixel_labels, p);
  scan.instance.clear();
}

}  // namespace slide::frontend
