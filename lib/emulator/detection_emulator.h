#pragma once
// Detection emulator: what a learned detector would output, made from the simulator's ground
// truth, for runs that stand a detector in (the sensor driver's --detections emulated). Seeded
// and deterministic: the same truth, parameters and seed give the same output.
//
// LiDAR (a RangeNet++-class range-image network): per-point SemanticKITTI labels and NO
// instance ids. Per ground-truth object: missed (all its points take the class's `missed_as`
// label) with a probability that grows with range and is 1 below a point count, or labelled
// wholly as a confused class; per point: label noise; in the range image (spherical
// projection, one pixel per beam and column): boundary bleeding (a point next to a pixel of
// another label takes that label), shadowing (points far behind the nearest point of their
// pixel take its label) and false-positive patches (a blob of one class labelled as another).
//
// RGBD (a YOLOv8-seg-class instance detector): per ground-truth instance mask, a detection
// probability that falls with the mask's median depth, with its occluded boundary fraction
// and to 0 below a pixel area; detected masks are eroded or dilated by a few pixels, may take
// a confused class, and carry a confidence score; false-positive masks appear at random.
// Instance ids in the output are 1..K in output order; object ids are 0 (a detector knows none).
//
// Parameters come from config/detections.yaml (loadDetectionEmulatorConfig), where the
// published figures they were calibrated to are cited.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "io/kitti_scan.h"

namespace slide::emulator {

// Errors of one SemanticKITTI label (a "thing" class: car, trunk, pole, ...).
struct LidarClassErrors {
  uint16_t label = 0;
  std::string name;
  double miss_near = 0.0;        // miss probability of a near object
  double miss_range = 1e9;       // metres (horizontal): half of the objects this far are missed
  double miss_width = 5.0;       // metres: width of the logistic rise
  int miss_min_points = 0;       // objects with fewer points are always missed
  uint16_t missed_as = 0;        // label a missed object's points take
  double bleed_out = 0.0;        // P(a boundary point of this class takes the neighbour's label)
  double bleed_in = 0.0;         // P(a point next to this class takes this class's label)
  double point_noise = 0.0;      // P(a point takes `missed_as` on its own)
  std::vector<std::pair<uint16_t, double>> confusion;  // per object: (label, probability)
  // Miss probability of an object `range` metres away with `points` points.
  double missProbability(double range, int points) const;
};

struct LidarFalsePositive {
  uint16_t from = 0, to = 0;  // a patch of `from` points is labelled `to`
  double per_scan = 0.0;      // mean patches per scan (Poisson)
  int radius_px = 2;          // patch radius in range-image pixels
  double depth_tolerance = 0.5;  // metres around the seed point's range
};

struct LidarEmulatorParams {
  int image_width = 1024, image_height = 64;  // range image (columns, rows)
  double shadow_gap = 1.0;          // metres behind the nearest point of a pixel ...
  double shadow_probability = 0.0;  // ... a point takes that point's label with this probability
  std::vector<LidarClassErrors> classes;
  std::vector<LidarFalsePositive> false_positives;
  const LidarClassErrors* find(uint16_t label) const;
};

// Errors of one detector class (class ids of config/classes.yaml).
struct RgbdClassErrors {
  int class_id = 0;
  std::string name;
  double detect_max = 0.95;      // detection probability of a near, unoccluded object
  double detect_range = 1e9;     // metres (median depth) where it has halved
  double detect_width = 1.0;     // metres: width of the logistic fall
  double occlusion_weight = 0.0; // detection probability *= 1 - weight * occluded boundary fraction
  int boundary_px = 0;           // masks are eroded or dilated by up to this many pixels
  std::vector<std::pair<int, double>> confusion;  // (class id, probability)
  // Detection probability at median depth `depth` with occluded boundary fraction `occluded`.
  double detectProbability(double depth, double occluded) const;
};

struct RgbdEmulatorParams {
  int min_area_px = 150;           // smaller masks are never detected
  double occlusion_gap = 0.15;     // metres: a boundary pixel whose outside neighbour is nearer by
                                   // this much (or lies on the image border) counts as occluded
  double score_threshold = 0.25;   // detections below this confidence are not output
  double confidence_sigma = 0.08;  // confidence = detection probability + N(0, sigma), clamped
  double false_positives_per_frame = 0.0;  // Poisson mean
  std::vector<int> false_positive_classes;
  int false_positive_radius_px = 25;
  double false_positive_max_confidence = 0.5;
  std::vector<RgbdClassErrors> classes;
  const RgbdClassErrors* find(int class_id) const;
};

struct DetectionEmulatorConfig {
  uint64_t seed = 1;
  LidarEmulatorParams lidar;
  RgbdEmulatorParams rgbd;
};

// Reads config/detections.yaml-style files; throws ConfigError naming file and key.
DetectionEmulatorConfig loadDetectionEmulatorConfig(const std::string& path);
// The seed of one frame's emulation: depends only on the config seed, robot and frame.
uint64_t detectionSeed(uint64_t seed, int robot, int frame);

// Emulated labels of a ground-truth labelled scan (same points, same order; `instance` all 0).
// A scan without labels comes back without labels.
io::LabelledScan emulateLidarLabels(const io::LabelledScan& truth, const LidarEmulatorParams& params, uint64_t seed);

// The RGBD function, emulateRgbdDetections, is in emulator/rgbd_emulator.h.

}  // namespace slide::emulator
