#include "rgbd_decode.h"

#include <random>

#include "clock/thread_cpu.h"
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

}  // namespace slide
