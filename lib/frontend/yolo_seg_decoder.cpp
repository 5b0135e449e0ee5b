#include "frontend/yolo_seg_decoder.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "frontend/mat_shape.h"

namespace slide::frontend {

namespace {
struct Candidate {
  int anchor, cls;
  float score;
  cv::Rect2d box;  // network-input pixels
};

// Greedy NMS within each class: candidates sorted by score, each kept unless a kept one of its
// class overlaps it by more than `iou`.
std::vector<Candidate> suppress(std::vector<Candidate> c, double iou, int max_keep) {
  std::stable_sort(c.begin(), c.end(), [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  std::vector<Candidate> kept;
  for (const auto& x : c) {
    if (static_cast<int>(kept.size()) >= max_keep) break;
    bool overlapped = false;
    for (const auto& k : kept) overlapped |= k.cls == x.cls && boxIou(k.box, x.box) > iou;
    if (!overlapped) kept.push_back(x);
  }
  return kept;
}
}  // namespace

Letterbox letterboxOf(int w, int h, int in_w, int in_h) {
  if (w <= 0 || h <= 0 || in_w <= 0 || in_h <= 0) throw std::invalid_argument("letterbox: sizes must be positive");
  Letterbox lb;
  lb.scale = std::min(double(in_w) / w, double(in_h) / h);
  lb.width = std::max(1, static_cast<int>(std::lround(w * lb.scale)));
  lb.height = std::max(1, static_cast<int>(std::lround(h * lb.scale)));
  lb.pad_x = (in_w - lb.width) / 2;
  lb.pad_y = (in_h - lb.height) / 2;
  return lb;
}

cv::Mat letterboxImage(const cv::Mat& bgr, const Letterbox& lb, int in_w, int in_h) {
  cv::Mat out(in_h, in_w, CV_8UC3, cv::Scalar(114, 114, 114)), scaled;
  cv::resize(bgr, scaled, cv::Size(lb.width, lb.height), 0, 0, cv::INTER_LINEAR);
  scaled.copyTo(out(cv::Rect(lb.pad_x, lb.pad_y, lb.width, lb.height)));
  return out;
}

double boxIou(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area(), uni = a.area() + b.area() - inter;
  return uni > 0 ? inter / uni : 0.0;
}

std::vector<YoloInstance> decodeYoloSeg(const cv::Mat& out0, const cv::Mat& out1, int classes, const Letterbox& lb, int image_w,
                                        int image_h, const YoloSegParams& p) {
  const int rows = 4 + classes + 32;
  if (out0.type() != CV_32F || out0.dims != 3 || out0.size[0] != 1 || out0.size[1] != rows)
    throw std::invalid_argument("YOLOv8-seg output0 " + shapeText(out0) + ": expected float [1, " + std::to_string(rows) +
                                " (4 box + " + std::to_string(classes) + " classes + 32 mask coefficients), anchors]");
  if (out1.type() != CV_32F || out1.dims != 4 || out1.size[0] != 1 || out1.size[1] != 32 || out1.size[2] < 1 || out1.size[3] < 1)
    throw std::invalid_argument("YOLOv8-seg output1 " + shapeText(out1) + ": expected float [1, 32, mask height, mask width]");
  const int anchors = out0.size[2];
  const float* d = out0.ptr<float>();
  auto at = [&](int row, int a) { return d[static_cast<std::size_t>(row) * anchors + a]; };
  std::vector<Candidate> cand;
  for (int a = 0; a < anchors; ++a) {
    int best = 0;
    for (int c = 1; c < classes; ++c)
      if (at(4 + c, a) > at(4 + best, a)) best = c;
    const float score = at(4 + best, a);
    if (!(score >= p.score_threshold)) continue;
    const double cx = at(0, a), cy = at(1, a), bw = at(2, a), bh = at(3, a);
    if (!std::isfinite(cx + cy + bw + bh) || bw <= 0 || bh <= 0) continue;
    cand.push_back({a, best, score, cv::Rect2d(cx - bw / 2, cy - bh / 2, bw, bh)});
  }
  const std::vector<Candidate> kept = suppress(std::move(cand), p.nms_iou, std::max(0, p.max_detections));

  const int mh = out1.size[2], mw = out1.size[3];
  const float* protos = out1.ptr<float>();
  const std::size_t plane = static_cast<std::size_t>(mh) * mw;
  // Image pixel centre -> prototype coordinate (pixel centres at integers), one bilinear step
  // through the letterbox: the two resizes of the description fused.
  const double sx = double(mw) / p.input_width, sy = double(mh) / p.input_height;
  auto protoX = [&](int u) { return ((u + 0.5) * lb.scale + lb.pad_x) * sx - 0.5; };
  auto protoY = [&](int v) { return ((v + 0.5) * lb.scale + lb.pad_y) * sy - 0.5; };
  const cv::Rect image_rect(0, 0, image_w, image_h);
  std::vector<YoloInstance> out;
  for (const auto& k : kept) {
    YoloInstance inst;
    inst.model_class = k.cls;
    inst.score = k.score;
    const cv::Rect2d b((k.box.x - lb.pad_x) / lb.scale, (k.box.y - lb.pad_y) / lb.scale, k.box.width / lb.scale,
                       k.box.height / lb.scale);
    inst.box = b & cv::Rect2d(0, 0, image_w, image_h);
    inst.mask = cv::Mat::zeros(image_h, image_w, CV_8U);
    // Pixels whose centres lie inside the box.
    const cv::Rect crop = cv::Rect(cv::Point(static_cast<int>(std::ceil(b.x - 0.5)), static_cast<int>(std::ceil(b.y - 0.5))),
                                   cv::Point(static_cast<int>(std::ceil(b.x + b.width - 0.5)),
                                             static_cast<int>(std::ceil(b.y + b.height - 0.5)))) &
                          image_rect;
    if (crop.area() <= 0) {
      out.push_back(std::move(inst));
      continue;
    }
    // Sigmoid of the coefficients . prototypes over the prototype pixels the crop reads.
    auto clampX = [&](double x) { return std::clamp(static_cast<int>(std::floor(x)), 0, mw - 1); };
    auto clampY = [&](double y) { return std::clamp(static_cast<int>(std::floor(y)), 0, mh - 1); };
    const int x0 = clampX(protoX(crop.x)), x1 = std::min(mw - 1, clampX(protoX(crop.x + crop.width - 1)) + 1);
    const int y0 = clampY(protoY(crop.y)), y1 = std::min(mh - 1, clampY(protoY(crop.y + crop.height - 1)) + 1);
    const int pw = x1 - x0 + 1;
    std::vector<float> prob(static_cast<std::size_t>(pw) * (y1 - y0 + 1), 0.0f);
    for (int j = 0; j < 32; ++j) {
      const float c = at(4 + classes + j, k.anchor);
      const float* pj = protos + j * plane;
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) prob[(y - y0) * pw + (x - x0)] += c * pj[y * mw + x];
    }
    for (float& v : prob) v = 1.0f / (1.0f + std::exp(-v));
    // Bilinear weights per crop column (border replicated, as cv::resize).
    std::vector<int> cx0(crop.width), cx1(crop.width);
    std::vector<float> wx(crop.width);
    for (int i = 0; i < crop.width; ++i) {
      const double x = std::clamp(protoX(crop.x + i), 0.0, double(mw - 1));
      cx0[i] = static_cast<int>(std::floor(x)), cx1[i] = std::min(cx0[i] + 1, mw - 1);
      wx[i] = static_cast<float>(x - cx0[i]);
      cx0[i] -= x0, cx1[i] -= x0;
    }
    for (int r = 0; r < crop.height; ++r) {
      const double y = std::clamp(protoY(crop.y + r), 0.0, double(mh - 1));
      const int ya = static_cast<int>(std::floor(y)), yb = std::min(ya + 1, mh - 1);
      const float wy = static_cast<float>(y - ya);
      const float* ra = prob.data() + (ya - y0) * pw;
      const float* rb = prob.data() + (yb - y0) * pw;
      std::uint8_t* m = inst.mask.ptr<std::uint8_t>(crop.y + r) + crop.x;
      for (int i = 0; i < crop.width; ++i) {
        const float top = ra[cx0[i]] + wx[i] * (ra[cx1[i]] - ra[cx0[i]]);
        const float bottom = rb[cx0[i]] + wx[i] * (rb[cx1[i]] - rb[cx0[i]]);
        if (top + wy * (bottom - top) > p.mask_threshold) m[i] = 255;
      }
    }
    out.push_back(std::move(inst));
  }
  return out;
}

void paintInstances(const std::vector<YoloInstance>& instances, const std::vector<int>& class_of_model, RgbdFrame& f) {
  const int w = f.intrinsics.width, h = f.intrinsics.height;
  if (f.mask.size() != static_cast<std::size_t>(std::max(0, w)) * std::max(0, h)) f.mask.assign(std::size_t(std::max(0, w)) * std::max(0, h), 0);
  for (const auto& inst : instances) {  // by descending score: earlier masks keep their pixels
    if (inst.model_class < 0 || inst.model_class >= static_cast<int>(class_of_model.size())) continue;
    const int ours = class_of_model[inst.model_class];
    if (ours < 0 || inst.mask.rows != h || inst.mask.cols != w || f.instance_class.size() >= 65535) continue;
    f.instance_class.push_back(ours);
    f.instance_confidence.push_back(inst.score);
    const auto id = static_cast<std::uint16_t>(f.instance_class.size());
    for (int v = 0; v < h; ++v) {
      const std::uint8_t* m = inst.mask.ptr<std::uint8_t>(v);
      std::uint16_t* out = f.mask.data() + static_cast<std::size_t>(v) * w;
      for (int u = 0; u < w; ++u)
        if (m[u] && out[u] == 0) out[u] = id;
    }
  }
}

}  // namespace slide::frontend
