#include "frontend/yolo_seg_decoder.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace slide {

namespace {
std::string shapeOf(const cv::Mat& m) {
  std::string t = "[";
  for (int d = 0; d < m.dims; ++d) t += (d ? ", " : "") + std::to_string(m.size[d]);
  return t + "]";
}

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
    throw std::invalid_argument("YOLOv8-seg output0 " + shapeOf(out0) + ": expected float [1, " + std::to_string(rows) +
                                " (4 box + " + std::to_string(classes) + " classes + 32 mask coefficients), anchors]");
  if (out1.type() != CV_32F || out1.dims != 4 || out1.size[0] != 1 || out1.size[1] != 32 || out1.size[2] < 1 || out1.size[3] < 1)
    throw std::invalid_argument("YOLOv8-seg output1 " + shapeOf(out1) + ": expected float [1, 32, mask height, mask width]");
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
  const cv::Mat protos(32, mh * mw, CV_32F, const_cast<float*>(out1.ptr<float>()));
  const cv::Rect image_rect(0, 0, image_w, image_h);
  std::vector<YoloInstance> out;
  for (const auto& k : kept) {
    cv::Mat coeff(1, 32, CV_32F);
    for (int j = 0; j < 32; ++j) coeff.at<float>(0, j) = at(4 + classes + j, k.anchor);
    const cv::Mat logit = cv::Mat(coeff * protos).reshape(1, mh);
    cv::Mat prob, input_size, image_size;
    cv::exp(-logit, prob);
    prob = 1.0 / (1.0 + prob);
    cv::resize(prob, input_size, cv::Size(p.input_width, p.input_height), 0, 0, cv::INTER_LINEAR);
    const cv::Rect inner = cv::Rect(lb.pad_x, lb.pad_y, lb.width, lb.height) & cv::Rect(0, 0, p.input_width, p.input_height);
    cv::resize(input_size(inner), image_size, cv::Size(image_w, image_h), 0, 0, cv::INTER_LINEAR);
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
    if (crop.area() > 0) {
      cv::Mat inside = image_size(crop) > p.mask_threshold;
      inside.copyTo(inst.mask(crop));
    }
    out.push_back(std::move(inst));
  }
  return out;
}

}  // namespace slide
