#include "frontend/semantic_seg_decoder.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "frontend/mat_shape.h"

namespace slide::frontend {

namespace {
// Nearest output index of each of `n` image pixels along one axis of `out` output pixels:
// floor((i + 0.5) * out / n), in integers.
std::vector<int> nearestCells(int n, int out) {
  std::vector<int> cell(n);
  for (int i = 0; i < n; ++i)
    cell[i] = static_cast<int>(std::min<long long>(out - 1, (2LL * i + 1) * out / (2LL * n)));
  return cell;
}
}  // namespace

PixelClasses classifyPixels(const cv::Mat& s, int classes, int image_w, int image_h, const SemanticSegParams& p) {
  if (image_w <= 0 || image_h <= 0) throw std::invalid_argument("semantic decoding: image sizes must be positive");
  if (s.type() != CV_32F || s.dims != 4 || s.size[0] != 1 || s.size[1] != classes || classes < 1 || s.size[2] < 1 ||
      s.size[3] < 1)
    throw std::invalid_argument("semantic scores " + shapeText(s) + ": expected float [1, " + std::to_string(classes) +
                                " classes, height, width]");
  // Best class and its probability per output pixel, one class plane at a time.
  const int h = s.size[2], w = s.size[3];
  const std::size_t n = static_cast<std::size_t>(h) * w;
  const float* d = s.ptr<float>();
  std::vector<int> best(n, 0);
  std::vector<float> top(d, d + n);
  for (int c = 1; c < classes; ++c) {
    const float* __restrict plane = d + c * n;
    float* __restrict t = top.data();
    int* __restrict b = best.data();
    for (std::size_t i = 0; i < n; ++i) {  // branch-free (a bit mask), so that the compiler vectorises it
      const float x = plane[i], y = t[i];
      const int higher = -static_cast<int>(x > y);  // all ones where class c scores higher
      b[i] = (c & higher) | (b[i] & ~higher);
      t[i] = x > y ? x : y;
    }
  }
  std::vector<float> prob = top;
  if (p.logits) {  // softmax of the winner: 1 / sum_c exp(score_c - top), OpenCV's vectorised exp
    const int len = static_cast<int>(n);
    const cv::Mat top_row(1, len, CV_32F, top.data());
    cv::Mat sum(1, len, CV_32F, cv::Scalar(0)), e;
    for (int c = 0; c < classes; ++c) {
      cv::subtract(cv::Mat(1, len, CV_32F, const_cast<float*>(d + c * n)), top_row, e);
      cv::exp(e, e);
      sum += e;
    }
    const float* s_sum = sum.ptr<float>();
    for (std::size_t i = 0; i < n; ++i) prob[i] = 1.0f / s_sum[i];
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!(prob[i] >= p.min_confidence)) best[i] = -1, prob[i] = 0.0f;  // NaN scores too

  PixelClasses out;
  out.width = image_w, out.height = image_h;
  out.model_class.resize(static_cast<std::size_t>(image_w) * image_h);
  out.probability.resize(out.model_class.size());
  const std::vector<int> col = nearestCells(image_w, w), row = nearestCells(image_h, h);
  for (int v = 0; v < image_h; ++v) {
    const std::size_t src = static_cast<std::size_t>(row[v]) * w, dst = static_cast<std::size_t>(v) * image_w;
    for (int u = 0; u < image_w; ++u) {
      out.model_class[dst + u] = best[src + col[u]];
      out.probability[dst + u] = prob[src + col[u]];
    }
  }
  return out;
}

std::vector<SemanticInstance> depthComponents(const PixelClasses& px, const std::vector<std::uint16_t>& depth,
                                              double depth_scale, const SemanticSegParams& p) {
  const int w = px.width, h = px.height;
  const std::size_t n = static_cast<std::size_t>(std::max(0, w)) * std::max(0, h);
  if (n == 0 || depth.size() != n || px.model_class.size() != n || px.probability.size() != n || !(depth_scale > 0))
    return {};
  // The depth step in raw units: |a - b| <= max(step, fraction * min(a, b)).
  const double step = p.depth_step_m / depth_scale;
  auto close = [&](std::uint16_t a, std::uint16_t b) {
    return std::abs(int(a) - int(b)) <= std::max(step, p.depth_step_fraction * std::min(a, b));
  };
  std::vector<std::uint8_t> seen(n, 0);
  std::vector<int> stack;
  std::vector<SemanticInstance> out;
  for (std::size_t start = 0; start < n; ++start) {
    if (seen[start] || px.model_class[start] < 0 || depth[start] == 0) continue;
    SemanticInstance inst;
    inst.model_class = px.model_class[start];
    double sum = 0;
    seen[start] = 1;
    stack.assign(1, static_cast<int>(start));
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      inst.pixels.push_back(i);
      sum += px.probability[i];
      const int u = i % w, v = i / w;
      auto visit = [&](int j) {
        if (!seen[j] && px.model_class[j] == inst.model_class && depth[j] != 0 && close(depth[i], depth[j]))
          seen[j] = 1, stack.push_back(j);
      };
      if (u > 0) visit(i - 1);
      if (u + 1 < w) visit(i + 1);
      if (v > 0) visit(i - w);
      if (v + 1 < h) visit(i + w);
    }
    if (static_cast<int>(inst.pixels.size()) < p.min_pixels) continue;
    inst.confidence = static_cast<float>(sum / inst.pixels.size());
    out.push_back(std::move(inst));
  }
  return out;
}

void paintSemanticInstances(const std::vector<SemanticInstance>& instances, const std::vector<int>& class_of_model,
                            RgbdFrame& f) {
  const std::size_t n = static_cast<std::size_t>(std::max(0, f.intrinsics.width)) * std::max(0, f.intrinsics.height);
  if (f.mask.size() != n) f.mask.assign(n, 0);
  for (const auto& inst : instances) {
    if (inst.model_class < 0 || inst.model_class >= static_cast<int>(class_of_model.size())) continue;
    const int ours = class_of_model[inst.model_class];
    if (ours < 0 || f.instance_class.size() >= 65535) continue;
    f.instance_class.push_back(ours);
    f.instance_confidence.push_back(inst.confidence);
    const auto id = static_cast<std::uint16_t>(f.instance_class.size());
    for (int i : inst.pixels)
      if (i >= 0 && static_cast<std::size_t>(i) < n && f.mask[i] == 0) f.mask[i] = id;
  }
}

}  // namespace slide::frontend
