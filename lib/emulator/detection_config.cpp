// Loader of config/detections.yaml (emulator/detection_emulator.h).
#include "config/config.h"
#include "emulator/detection_emulator.h"

namespace slide::emulator {

namespace {
void probability(const ConfigNode& n, const std::string& key, double& v) {
  n.read(key, v);
  if (!(v >= 0.0 && v <= 1.0)) n.fail(key, "must be a probability in [0, 1]");
}

uint16_t labelValue(const ConfigNode& n, const std::string& key, int v) {
  if (v < 0 || v > 65535) n.fail(key, "must be a SemanticKITTI label in 0..65535");
  return static_cast<uint16_t>(v);
}

// "confusion: {LABEL: P, ...}"; the probabilities must sum to at most 1.
template <typename Id>
std::vector<std::pair<Id, double>> confusion(const ConfigNode& n) {
  std::vector<std::pair<Id, double>> out;
  if (!n.has("confusion")) return out;
  const ConfigNode c = n.child("confusion");
  double sum = 0;
  for (const std::string& k : c.keys()) {
    int id = 0;
    try {
      id = std::stoi(k);
    } catch (const std::exception&) {
      c.fail(k, "expected a numeric label or class id");
    }
    double p = 0;
    probability(c, k, p);
    sum += p;
    out.emplace_back(static_cast<Id>(id), p);
  }
  if (sum > 1.0 + 1e-9) n.fail("confusion", "probabilities sum to more than 1");
  return out;
}

LidarEmulatorParams loadLidar(const ConfigNode& n) {
  LidarEmulatorParams p;
  n.read("image_width", p.image_width);
  n.read("image_height", p.image_height);
  if (p.image_width < 8 || p.image_height < 2) n.fail("image_width", "range image must be at least 8 x 2 pixels");
  n.read("shadow_gap", p.shadow_gap);
  n.requireNonNegative("shadow_gap", p.shadow_gap);
  probability(n, "shadow_probability", p.shadow_probability);
  if (n.has("classes")) {
    const ConfigNode list = n.child("classes");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const ConfigNode c = list[i];
      LidarClassErrors e;
      e.label = labelValue(c, "label", c.get<int>("label"));
      e.name = c.get<std::string>("name", std::to_string(e.label));
      probability(c, "miss_near", e.miss_near);
      c.read("miss_range", e.miss_range);
      c.read("miss_width", e.miss_width);
      c.requirePositive("miss_width", e.miss_width);
      c.read("miss_min_points", e.miss_min_points);
      e.missed_as = labelValue(c, "missed_as", c.get<int>("missed_as", 0));
      probability(c, "bleed_out", e.bleed_out);
      probability(c, "bleed_in", e.bleed_in);
      probability(c, "point_noise", e.point_noise);
      e.confusion = confusion<uint16_t>(c);
      if (p.find(e.label)) c.fail("label", "label " + std::to_string(e.label) + " listed twice");
      p.classes.push_back(e);
    }
  }
  if (n.has("false_positives")) {
    const ConfigNode list = n.child("false_positives");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const ConfigNode c = list[i];
      LidarFalsePositive f;
      f.from = labelValue(c, "from", c.get<int>("from"));
      f.to = labelValue(c, "to", c.get<int>("to"));
      c.read("per_scan", f.per_scan);
      c.requireNonNegative("per_scan", f.per_scan);
      c.read("radius_px", f.radius_px);
      if (f.radius_px < 0 || f.radius_px > 50) c.fail("radius_px", "must be in 0..50");
      c.read("depth_tolerance", f.depth_tolerance);
      p.false_positives.push_back(f);
    }
  }
  return p;
}

RgbdEmulatorParams loadRgbd(const ConfigNode& n) {
  RgbdEmulatorParams p;
  n.read("min_area_px", p.min_area_px);
  n.read("occlusion_gap", p.occlusion_gap);
  n.requireNonNegative("occlusion_gap", p.occlusion_gap);
  probability(n, "score_threshold", p.score_threshold);
  n.read("confidence_sigma", p.confidence_sigma);
  n.requireNonNegative("confidence_sigma", p.confidence_sigma);
  n.read("false_positives_per_frame", p.false_positives_per_frame);
  n.requireNonNegative("false_positives_per_frame", p.false_positives_per_frame);
  if (n.has("false_positive_classes")) p.false_positive_classes = n.getList<int>("false_positive_classes");
  n.read("false_positive_radius_px", p.false_positive_radius_px);
  if (p.false_positive_radius_px < 3 || p.false_positive_radius_px > 200) n.fail("false_positive_radius_px", "must be in 3..200");
  probability(n, "false_positive_max_confidence", p.false_positive_max_confidence);
  if (n.has("classes")) {
    const ConfigNode list = n.child("classes");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const ConfigNode c = list[i];
      RgbdClassErrors e;
      e.class_id = c.get<int>("class");
      e.name = c.get<std::string>("name", std::to_string(e.class_id));
      probability(c, "detect_max", e.detect_max);
      c.read("detect_range", e.detect_range);
      c.read("detect_width", e.detect_width);
      c.requirePositive("detect_width", e.detect_width);
      probability(c, "occlusion_weight", e.occlusion_weight);
      c.read("boundary_px", e.boundary_px);
      if (e.boundary_px < 0 || e.boundary_px > 20) c.fail("boundary_px", "must be in 0..20");
      e.confusion = confusion<int>(c);
      if (p.find(e.class_id)) c.fail("class", "class " + std::to_string(e.class_id) + " listed twice");
      p.classes.push_back(e);
    }
  }
  return p;
}
}  // namespace

DetectionEmulatorConfig loadDetectionEmulatorConfig(const std::string& path) {
  const ConfigNode root = ConfigNode::load(path);
  DetectionEmulatorConfig cfg;
  if (root.has("seed")) {
    const long s = root.get<long>("seed");
    if (s < 0) root.fail("seed", "must be non-negative");
    cfg.seed = static_cast<uint64_t>(s);
  }
  if (root.has("lidar")) cfg.lidar = loadLidar(root.child("lidar"));
  if (root.has("rgbd")) cfg.rgbd = loadRgbd(root.child("rgbd"));
  root.rejectUnknownKeys();
  return cfg;
}

}  // namespace slide::emulator
