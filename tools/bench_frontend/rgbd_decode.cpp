#include "rgbd_decode.h"

#include <random>

#include "clock/thread_cpu.h"
#include "frontend/semantic_seg_decoder.h"
#include "frontend/yolo_seg_decoder.h"

namespace slide {

std::vector<double> timeRgbdDecode(const ClassTable& classes, const frontend::FrontendConfig& cfg, int runs,
                                   int objects) {
  const int w = 640, h = 480, nc = 80, anchors = 8400, rows = 4 + nc + 32;
  std::mt19937 rng(19);
  std::uniform_real_distribution<float> low(0.0f, 0.2f);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  const int dims0[3] = {1, rows, anchors}, dims1[4] = {1, 32, 160, 160};
  cv::Mat out0(3, dims0, CV_32F), out1(4, dims1, CV_32F);
  float* d = out0.ptr<float>();
  for (int r = 0; r < rows; ++r)
    for (int a = 0; a < anchors; ++a) d[r * anchors + a] = r < 4 ? 40.0f : r < 4 + nc ? low(rng) : normal(rng);
  for (int k = 0; k < objects; ++k) {  // a grid of confident boxes
    const int a = k * (anchors / objects);
    d[0 * anchors + a] = 60.0f + 110.0f * (k % 5), d[1 * anchors + a] = 160.0f + 200.0f * (k / 5);
    d[2 * anchors + a] = 100.0f, d[3 * anchors + a] = 120.0f;
    d[(4 + 56) * anchors + a] = 0.9f;  // COCO chair
  }
  float* q = out1.ptr<float>();
  for (std::size_t i = 0; i < out1.total(); ++i) q[i] = normal(rng);
  std::vector<int> class_of_model(nc, -1);
  class_of_model[56] = classes.findByName("chair")->id;
  frontend::YoloSegParams p;
  const frontend::Letterbox lb = frontend::letterboxOf(w, h, p.input_width, p.input_height);
  frontend::RgbdFrame base;
  base.intrinsics = {w, h, 380.0, 380.0, 320.0, 240.0, 0.001};
  base.depth.assign(static_cast<std::size_t>(w) * h, 2000);
  std::vector<double> ms;
  for (int run = 0; run < runs; ++run) {
    frontend::RgbdFrame f = base;
    const double c0 = clock::threadCpuMs();
    frontend::paintInstances(frontend::decodeYoloSeg(out0, out1, nc, lb, w, h, p), class_of_model, f);
    frontend::InputIssues issues;
    frontend::segmentRgbd(f, classes, cfg.rgbd, issues);
    ms.push_back(clock::threadCpuMs() - c0);
  }
  return ms;
}

std::vector<double> timeSemanticDecode(const ClassTable& classes, const frontend::FrontendConfig& cfg, int runs,
                                       int output_factor, int objects) {
  const int w = 640, h = 480, nc = 40, ow = w / output_factor, oh = h / output_factor;
  const int chair = 1;  // model class 0: wall (none), 1: chair
  std::vector<cv::Rect> boxes;
  for (int k = 0; k < objects; ++k) boxes.emplace_back(10 + 125 * (k % 5), 40 + 220 * (k / 5), 100, 120);
  std::mt19937 rng(23);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  const int dims[4] = {1, nc, oh, ow};
  cv::Mat scores(4, dims, CV_32F);
  float* d = scores.ptr<float>();
  for (std::size_t i = 0; i < scores.total(); ++i) d[i] = normal(rng);
  const std::size_t plane = static_cast<std::size_t>(ow) * oh;
  frontend::RgbdFrame base;
  base.intrinsics = {w, h, 380.0, 380.0, 320.0, 240.0, 0.001};
  base.depth.assign(static_cast<std::size_t>(w) * h, 3000);
  for (const cv::Rect& b : boxes)
    for (int v = b.y; v < b.y + b.height; ++v)
      for (int u = b.x; u < b.x + b.width; ++u) base.depth[static_cast<std::size_t>(v) * w + u] = 2000;
  for (int v = 0; v < oh; ++v)  // the winner 6 above the rest
    for (int u = 0; u < ow; ++u) {
      const int cls = base.depth[static_cast<std::size_t>(v * output_factor) * w + u * output_factor] == 2000 ? chair : 0;
      d[cls * plane + static_cast<std::size_t>(v) * ow + u] += 6.0f;
    }
  std::vector<int> class_of_model(nc, -1);
  class_of_model[chair] = classes.findByName("chair")->id;
  frontend::SemanticSegParams p;
  std::vector<double> ms;
  for (int run = 0; run < runs; ++run) {
    frontend::RgbdFrame f = base;
    const double c0 = clock::threadCpuMs();
    frontend::paintSemanticInstances(
        frontend::depthComponents(frontend::classifyPixels(scores, nc, w, h, p), f.depth, f.intrinsics.depth_scale, p),
        class_of_model, f);
    frontend::InputIssues issues;
    frontend::segmentRgbd(f, classes, cfg.rgbd, issues);
    ms.push_back(clock::threadCpuMs() - c0);
  }
  return ms;
}

}  // namespace slide
