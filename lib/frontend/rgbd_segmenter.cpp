#include "frontend/rgbd_segmenter.h"

#include <algorithm>
#include <cmath>

#include "frontend/depth_filter.h"
#include "frontend/point_stats.h"

namespace slide::frontend {

namespace {
// Is a pixel of another id (or the image border) within `r` pixels (square window) of (u, v)?
bool onMaskEdge(const std::vector<std::uint16_t>& mask, int w, int h, int u, int v, int r) {
  const std::uint16_t id = mask[static_cast<std::size_t>(v) * w + u];
  if (u < r || v < r || u + r >= w || v + r >= h) return true;
  for (int dv = -r; dv <= r; ++dv)
    for (int du = -r; du <= r; du += (dv == -r || dv == r) ? 1 : 2 * r)  // the window's border ring
      if (mask[static_cast<std::size_t>(v + dv) * w + u + du] != id) return true;
  return false;
}
}  // namespace

bool resetDetections(RgbdFrame& f) {
  const int w = f.intrinsics.width, h = f.intrinsics.height;
  f.instance_class.clear();
  f.instance_confidence.clear();
  f.mask.assign(static_cast<std::size_t>(std::max(0, w)) * std::max(0, h), 0);
  return w > 0 && h > 0 && f.color.size() == f.mask.size() * 3;
}

std::vector<Instance> segmentRgbd(const RgbdFrame& f, const ClassTable& classes, const RgbdSegmenterParams& p,
                                  InputIssues& issues) {
  const CameraIntrinsics& K = f.intrinsics;
  if (K.width <= 0 || K.height <= 0 || !(K.fx > 0) || !(K.fy > 0) || !(K.depth_scale > 0)) {
    issues.count("invalid intrinsics");
    return {};
  }
  const std::size_t n = static_cast<std::size_t>(K.width) * K.height;
  if (f.depth.size() != n || f.mask.size() != n) {
    issues.count("image size does not match intrinsics");
    return {};
  }
  if (f.instance_confidence.size() != f.instance_class.size()) {
    issues.count("instance arrays differ in length");
    return {};
  }
  const std::vector<std::uint16_t> depth = medianDepthWithinMasks(f.depth, f.mask, K.width, K.height, p.median_radius);
  const int num = static_cast<int>(f.instance_class.size());
  std::vector<std::vector<int>> pixels(num), edges(num);
  long missing_depth = 0, stray_ids = 0;
  const int stride = std::max(1, p.stride);
  for (int v = 0; v < K.height; v += stride)
    for (int u = 0; u < K.width; u += stride) {
      const std::size_t i = static_cast<std::size_t>(v) * K.width + u;
      const int id = f.mask[i];
      if (id == 0) continue;
      if (id > num) {
        ++stray_ids;
        continue;
      }
      const bool edge = p.erode_px > 0 && onMaskEdge(f.mask, K.width, K.height, u, v, p.erode_px);
      if (depth[i] == 0) {
        missing_depth += !edge;  // edge pixels often fall beyond the object: not counted
        continue;
      }
      (edge ? edges : pixels)[id - 1].push_back(static_cast<int>(i));
    }
  issues.count("zero depth in mask", missing_depth);
  issues.count("mask id without instance", stray_ids);

  std::vector<Instance> out;
  for (int k = 0; k < num; ++k) {
    if (!classes.find(f.instance_class[k])) {
      issues.count("unknown class");
      continue;
    }
    if (!(f.instance_confidence[k] >= p.min_confidence) || static_cast<int>(pixels[k].size()) < p.min_points) continue;
    std::vector<double> d;
    d.reserve(pixels[k].size());
    for (int i : pixels[k]) d.push_back(depth[i] * K.depth_scale);
    std::vector<double> tmp = d;
    const double lo = std::max(p.min_depth, quantileInPlace(tmp, 0.5 - 0.5 * p.band_fraction) - p.band_margin);
    const double hi = std::min(p.max_depth, quantileInPlace(tmp, 0.5 + 0.5 * p.band_fraction) + p.band_margin);
    Instance inst;
    inst.id = k + 1;
    inst.class_id = f.instance_class[k];
    inst.confidence = f.instance_confidence[k];
    auto add = [&](int i, double z) {
      if (z < lo || z > hi) return;
      const int u = i % K.width, v = i / K.width;
      const double x_opt = (u - K.cx) * z / K.fx, y_opt = (v - K.cy) * z / K.fy;
      inst.points.emplace_back(static_cast<float>(z), static_cast<float>(-x_opt), static_cast<float>(-y_opt));
    };
    for (std::size_t j = 0; j < pixels[k].size(); ++j) add(pixels[k][j], d[j]);
    // Edge pixels: on the object when their own (unfiltered) depth lies in the object's band;
    // spilled onto the background behind (or an occluder in front) when not. Dropping them
    // all would narrow every object by erode_px pixels a side, and its centre, completed from
    // its width, would land short.
    if (p.restore_edges)
      for (int i : edges[k]) add(i, f.depth[i] * K.depth_scale);
    if (static_cast<int>(inst.points.size()) >= p.min_points) out.push_back(std::move(inst));
  }
  return out;
}

}  // namespace slide::frontend
