// RGBD half of the detection emulator (emulator/detection_emulator.h): YOLOv8-seg-class masks.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "emulator/rgbd_emulator.h"
#include "emulator/fast_rng.h"

namespace slide::emulator {

double RgbdClassErrors::detectProbability(double depth, double occluded) const {
  const double near = 1.0 / (1.0 + std::exp((depth - detect_range) / std::max(detect_width, 1e-6)));
  return std::clamp(detect_max * near * (1.0 - occlusion_weight * std::clamp(occluded, 0.0, 1.0)), 0.0, 1.0);
}

const RgbdClassErrors* RgbdEmulatorParams::find(int class_id) const {
  for (const auto& c : classes)
    if (c.class_id == class_id) return &c;
  return nullptr;
}

namespace {
struct TruthInstance {
  int area = 0;
  std::vector<float> depths;
  int boundary = 0, occluded = 0;
  cv::Rect box;
};

// Area, depths, bounding box and occluded boundary of every instance of `ids`.
std::vector<TruthInstance> describe(const cv::Mat& ids, const cv::Mat& depth, double scale, int count, double gap) {
  std::vector<TruthInstance> out(count);
  std::vector<int> x0(count, ids.cols), y0(count, ids.rows), x1(count, -1), y1(count, -1);
  for (int v = 0; v < ids.rows; ++v)
    for (int u = 0; u < ids.cols; ++u) {
      const int id = ids.at<uint16_t>(v, u);
      if (id == 0 || id > count) continue;
      TruthInstance& t = out[id - 1];
      ++t.area;
      x0[id - 1] = std::min(x0[id - 1], u), y0[id - 1] = std::min(y0[id - 1], v);
      x1[id - 1] = std::max(x1[id - 1], u), y1[id - 1] = std::max(y1[id - 1], v);
      const double z = depth.at<uint16_t>(v, u) * scale;
      if (z > 0) t.depths.push_back(static_cast<float>(z));
      bool edge = false, hidden = false;
      for (const auto& [du, dv] : {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1}}) {
        const int uu = u + du, vv = v + dv;
        if (uu < 0 || vv < 0 || uu >= ids.cols || vv >= ids.rows) {
          edge = hidden = true;  // cut by the image border
          continue;
        }
        if (ids.at<uint16_t>(vv, uu) == id) continue;
        edge = true;
        const double zn = depth.at<uint16_t>(vv, uu) * scale;
        if (zn > 0 && z > 0 && zn < z - gap) hidden = true;
      }
      t.boundary += edge;
      t.occluded += hidden;
    }
  for (int k = 0; k < count; ++k)
    if (x1[k] >= 0) out[k].box = cv::Rect(x0[k], y0[k], x1[k] - x0[k] + 1, y1[k] - y0[k] + 1);
  return out;
}

float median(std::vector<float> v) {
  if (v.empty()) return 0.f;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}
}  // namespace

EmulatedMasks emulateRgbdDetections(const io::InstanceMask& truth, const cv::Mat& depth, double depth_scale,
                                    const RgbdEmulatorParams& p, uint64_t seed) {
  if (truth.mask.empty() || truth.mask.type() != CV_16UC1 || depth.type() != CV_16UC1 || truth.mask.size() != depth.size())
    throw std::invalid_argument("emulateRgbdDetections: mask and depth must be 16-bit images of one size");
  FastRng rng(seed);
  const int count = static_cast<int>(truth.class_id.size());
  const std::vector<TruthInstance> inst = describe(truth.mask, depth, depth_scale, count, p.occlusion_gap);
  EmulatedMasks out;
  out.masks.mask = cv::Mat::zeros(truth.mask.size(), CV_16UC1);
  auto add = [&](const cv::Mat& binary, const cv::Rect& roi, int class_id, float confidence) {
    const uint16_t id = static_cast<uint16_t>(out.masks.class_id.size() + 1);
    cv::Mat target = out.masks.mask(roi);
    int area = 0;
    for (int v = 0; v < binary.rows; ++v)
      for (int u = 0; u < binary.cols; ++u)
        if (binary.at<uint8_t>(v, u) && target.at<uint16_t>(v, u) == 0) target.at<uint16_t>(v, u) = id, ++area;
    if (area == 0) return;
    out.masks.class_id.push_back(class_id);
    out.masks.object_id.push_back(0);
    out.confidence.push_back(confidence);
  };

  for (int k = 0; k < count; ++k) {
    const TruthInstance& t = inst[k];
    const RgbdClassErrors* c = p.find(truth.class_id[k]);
    if (!c || t.area < p.min_area_px) continue;
    const double occluded = t.boundary ? static_cast<double>(t.occluded) / t.boundary : 0.0;
    const double pd = c->detectProbability(median(t.depths), occluded);
    if (!rng.chance(pd)) continue;
    int cls = c->class_id;
    double u = rng.uniform();
    for (const auto& [to, prob] : c->confusion) {
      if (u < prob) {
        cls = to;
        break;
      }
      u -= prob;
    }
    const int shift = c->boundary_px > 0 ? rng.below(2 * c->boundary_px + 1) - c->boundary_px : 0;
    const int pad = std::abs(shift) + 1;
    const cv::Rect roi = (t.box + cv::Point(-pad, -pad) + cv::Size(2 * pad, 2 * pad)) & cv::Rect(0, 0, depth.cols, depth.rows);
    cv::Mat binary = (truth.mask(roi) == (k + 1));
    if (shift != 0) {
      const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * std::abs(shift) + 1, 2 * std::abs(shift) + 1));
      if (shift < 0) cv::erode(binary, binary, kernel);
      else cv::dilate(binary, binary, kernel);
    }
    const float conf = static_cast<float>(std::clamp(pd + p.confidence_sigma * rng.normal(), p.score_threshold, 0.99));
    add(binary, roi, cls, conf);
  }

  if (!p.false_positive_classes.empty())
    for (int k = rng.poisson(p.false_positives_per_frame); k > 0; --k) {
      const int u0 = rng.below(depth.cols), v0 = rng.below(depth.rows);
      const double z0 = depth.at<uint16_t>(v0, u0) * depth_scale;
      if (!(z0 > 0)) continue;
      const int ru = std::max(3, static_cast<int>(p.false_positive_radius_px * (0.5 + 0.5 * rng.uniform())));
      const int rv = std::max(3, static_cast<int>(p.false_positive_radius_px * (0.5 + 0.5 * rng.uniform())));
      const cv::Rect roi = cv::Rect(u0 - ru, v0 - rv, 2 * ru + 1, 2 * rv + 1) & cv::Rect(0, 0, depth.cols, depth.rows);
      cv::Mat binary = cv::Mat::zeros(roi.size(), CV_8UC1);
      int area = 0;
      for (int v = 0; v < roi.height; ++v)
        for (int u = 0; u < roi.width; ++u) {
          const double du = double(u + roi.x - u0) / ru, dv = double(v + roi.y - v0) / rv;
          const double z = depth.at<uint16_t>(v + roi.y, u + roi.x) * depth_scale;
          if (du * du + dv * dv <= 1.0 && z > 0 && std::abs(z - z0) < 0.3) binary.at<uint8_t>(v, u) = 1, ++area;
        }
      if (area < p.min_area_px) continue;
      const int cls = p.false_positive_classes[rng.below(static_cast<int>(p.false_positive_classes.size()))];
      const double hi = std::max(p.score_threshold, p.false_positive_max_confidence);
      add(binary, roi, cls, static_cast<float>(p.score_threshold + (hi - p.score_threshold) * rng.uniform()));
    }
  return out;
}

}  // namespace slide::emulator
