// LiDAR half of the detection emulator (emulator/detection_emulator.h): RangeNet++-class labels.
#include <cmath>
#include <unordered_map>

#include "emulator/detection_emulator.h"
#include "emulator/fast_rng.h"

namespace slide::emulator {

double LidarClassErrors::missProbability(double range, int points) const {
  if (points < miss_min_points) return 1.0;
  const double far = 1.0 / (1.0 + std::exp(-(range - miss_range) / std::max(miss_width, 1e-6)));
  return std::clamp(miss_near + (1.0 - miss_near) * far, 0.0, 1.0);
}

const LidarClassErrors* LidarEmulatorParams::find(uint16_t label) const {
  for (const auto& c : classes)
    if (c.label == label) return &c;
  return nullptr;
}

uint64_t detectionSeed(uint64_t seed, int robot, int frame) {
  FastRng r(seed ^ (0x51ed2701ULL * (static_cast<uint64_t>(robot) + 1)) ^ (static_cast<uint64_t>(frame) << 24));
  r.next();
  return r.next();
}

namespace {
// Spherical projection: pixel of every point (-1 for a degenerate point) and the nearest
// point of every pixel.
struct RangeImage {
  int width = 0, height = 0;
  std::vector<int> pixel, nearest;
  std::vector<float> range;
};

RangeImage project(const io::LabelledScan& s, int width, int height) {
  RangeImage im;
  im.width = std::max(width, 8);
  im.height = std::max(height, 2);
  const std::size_t n = s.size();
  im.pixel.assign(n, -1);
  im.range.assign(n, 0.f);
  std::vector<float> elev(n, 0.f);
  float lo = 1e9f, hi = -1e9f;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f& p = s.xyz[i];
    const float r = p.norm();
    if (!std::isfinite(r) || r < 1e-3f) continue;
    im.range[i] = r;
    elev[i] = std::asin(std::clamp(p.z() / r, -1.f, 1.f));
    lo = std::min(lo, elev[i]);
    hi = std::max(hi, elev[i]);
  }
  const float span = std::max(hi - lo, 1e-3f);
  im.nearest.assign(static_cast<std::size_t>(im.width) * im.height, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (im.range[i] <= 0) continue;
    const Eigen::Vector3f& p = s.xyz[i];
    const double az = std::atan2(p.y(), p.x()) + M_PI;  // [0, 2 pi]
    const int col = std::min(im.width - 1, static_cast<int>(az / (2 * M_PI) * im.width));
    const int row = std::clamp(static_cast<int>(std::lround((hi - elev[i]) / span * (im.height - 1))), 0, im.height - 1);
    const int px = row * im.width + col;
    im.pixel[i] = px;
    int& best = im.nearest[px];
    if (best < 0 || im.range[i] < im.range[best]) best = static_cast<int>(i);
  }
  return im;
}

// Pixels next to `px` (left, right with wrap-around; up, down).
std::array<int, 4> neighbours(const RangeImage& im, int px) {
  const int row = px / im.width, col = px % im.width;
  return {row * im.width + (col + im.width - 1) % im.width, row * im.width + (col + 1) % im.width,
          row > 0 ? px - im.width : -1, row + 1 < im.height ? px + im.width : -1};
}
}  // namespace

io::LabelledScan emulateLidarLabels(const io::LabelledScan& truth, const LidarEmulatorParams& p, uint64_t seed) {
  io::LabelledScan out;
  out.xyz = truth.xyz;
  out.intensity = truth.intensity;
  if (!truth.hasLabels() || truth.semantic.size() != truth.size()) return out;
  const std::size_t n = truth.size();
  const bool has_instances = truth.instance.size() == n;
  FastRng rng(seed);

  // 1. Objects: missed with a probability growing with range, or confused as a whole.
  std::vector<uint16_t> label(truth.semantic.begin(), truth.semantic.end());
  if (has_instances) {
    struct Obj {
      uint16_t label = 0;
      std::vector<int> points;
      Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    };
    std::unordered_map<uint32_t, Obj> objects;
    std::vector<uint32_t> order;  // first-seen order: deterministic iteration
    for (std::size_t i = 0; i < n; ++i) {
      if (truth.instance[i] == 0 || !p.find(truth.semantic[i])) continue;
      const uint32_t key = (static_cast<uint32_t>(truth.instance[i]) << 16) | truth.semantic[i];
      auto [it, fresh] = objects.try_emplace(key);
      if (fresh) order.push_back(key), it->second.label = truth.semantic[i];
      it->second.points.push_back(static_cast<int>(i));
      if (truth.xyz[i].allFinite()) it->second.sum += truth.xyz[i].head<2>().cast<double>();
    }
    for (uint32_t key : order) {
      const Obj& o = objects[key];
      const LidarClassErrors& c = *p.find(o.label);
      const double range = (o.sum / static_cast<double>(o.points.size())).norm();
      uint16_t to = o.label;
      if (rng.chance(c.missProbability(range, static_cast<int>(o.points.size())))) {
        to = c.missed_as;
      } else {
        double u = rng.uniform();
        for (const auto& [l, prob] : c.confusion) {
          if (u < prob) {
            to = l;
            break;
          }
          u -= prob;
        }
      }
      if (to != o.label)
        for (int i : o.points) label[i] = to;
    }
  }
  // 2. Per-point label noise.
  for (std::size_t i = 0; i < n; ++i)
    if (const LidarClassErrors* c = p.find(label[i]); c && c->point_noise > 0 && rng.chance(c->point_noise))
      label[i] = c->missed_as;

  // 3. Range image: bleeding across boundaries, shadowing behind near points, false-positive patches.
  const RangeImage im = project(truth, p.image_width, p.image_height);
  std::vector<uint16_t> bled = label;
  for (std::size_t i = 0; i < n; ++i) {
    const int px = im.pixel[i];
    if (px < 0) continue;
    const int near = im.nearest[px];
    if (near != static_cast<int>(i)) {
      if (im.range[i] - im.range[near] > p.shadow_gap && label[near] != label[i] && rng.chance(p.shadow_probability))
        bled[i] = label[near];
      continue;
    }
    const LidarClassErrors* own = p.find(label[i]);
    const std::array<int, 4> nb = neighbours(im, px);
    const int start = rng.below(4);
    for (int k = 0; k < 4; ++k) {
      const int q = nb[(start + k) % 4];
      if (q < 0 || im.nearest[q] < 0) continue;
      const uint16_t other = label[im.nearest[q]];
      if (other == label[i]) continue;
      const LidarClassErrors* theirs = p.find(other);
      const double prob = own ? own->bleed_out : theirs ? theirs->bleed_in : 0.0;
      if (prob > 0 && rng.chance(prob)) bled[i] = other;
      break;  // one boundary decision per point
    }
  }
  for (const LidarFalsePositive& fp : p.false_positives) {
    std::vector<int> candidates;
    for (std::size_t px = 0; px < im.nearest.size(); ++px)
      if (im.nearest[px] >= 0 && label[im.nearest[px]] == fp.from) candidates.push_back(static_cast<int>(px));
    if (candidates.empty()) continue;
    for (int k = rng.poisson(fp.per_scan); k > 0; --k) {
      const int seed_px = candidates[rng.below(static_cast<int>(candidates.size()))];
      const float r0 = im.range[im.nearest[seed_px]];
      const int row0 = seed_px / im.width, col0 = seed_px % im.width;
      for (int dr = -fp.radius_px; dr <= fp.radius_px; ++dr)
        for (int dc = -fp.radius_px; dc <= fp.radius_px; ++dc) {
          const int row = row0 + dr;
          if (row < 0 || row >= im.height || dr * dr + dc * dc > fp.radius_px * fp.radius_px) continue;
          const int q = im.nearest[row * im.width + (col0 + dc + im.width) % im.width];
          if (q >= 0 && label[q] == fp.from && std::abs(im.range[q] - r0) <= fp.depth_tolerance) bled[q] = fp.to;
        }
    }
  }
  out.semantic = std::move(bled);
  out.instance.assign(n, 0);
  return out;
}

}  // namespace slide::emulator
