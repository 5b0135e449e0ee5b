// The detection emulator's measured error rates match its configuration on seeded samples:
// LiDAR miss rate against range, whole-object confusion, boundary bleeding, no instance ids,
// false-positive patches; RGBD miss rate against depth, boundary erosion/dilation, confusion,
// false positives and confidence; same seed, same output. And config/detections.yaml loads.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "emulator/detection_emulator.h"
#include "emulator/rgbd_emulator.h"

using namespace slide;

namespace {
// A scan of `count` box-shaped objects (label `label`, ids 1..count) standing on a ring of
// radius `range` around the sensor, each `w` columns by `h` rows of a 1024 x 64 image, in
// front of a vegetation background (label 70) filling the rest of each object's rows.
io::LabelledScan ringScan(int count, double range, uint16_t label, int w = 6, int h = 20) {
  io::LabelledScan s;
  const int cols = 1024, rows = 64;
  for (int c = 0; c < cols; ++c)
    for (int r = 0; r < rows; ++r) {
      const double az = 2 * M_PI * (c + 0.5) / cols - M_PI;
      const double el = (16.6 - 33.2 * r / (rows - 1)) * M_PI / 180;
      const int slot = c / (cols / count);
      const int within = c % (cols / count);
      const bool object = within < w && r >= 20 && r < 20 + h;
      const double d = object ? range : range + 5.0;
      s.xyz.emplace_back(d * std::cos(el) * std::cos(az), d * std::cos(el) * std::sin(az), d * std::sin(el));
      s.intensity.push_back(0.5f);
      s.semantic.push_back(object ? label : 70);
      s.instance.push_back(object ? slot + 1 : 0);
    }
  return s;
}

emulator::LidarClassErrors trunkErrors() {
  emulator::LidarClassErrors e;
  e.label = 71;
  e.miss_near = 0.1;
  e.miss_range = 30;
  e.miss_width = 4;
  e.missed_as = 70;
  return e;
}

// Per ground-truth object: the label most of its points carry in `out`.
std::map<int, uint16_t> majority(const io::LabelledScan& truth, const io::LabelledScan& out) {
  std::map<int, std::map<uint16_t, int>> votes;
  for (std::size_t i = 0; i < truth.size(); ++i)
    if (truth.instance[i]) ++votes[truth.instance[i]][out.semantic[i]];
  std::map<int, uint16_t> m;
  for (const auto& [id, v] : votes) {
    int best = -1;
    for (const auto& [l, n] : v)
      if (n > best) best = n, m[id] = l;
  }
  return m;
}
}  // namespace

TEST(LidarEmulator, MissRateFollowsRangeAndNoInstanceIds) {
  emulator::LidarEmulatorParams p;
  p.classes.push_back(trunkErrors());
  for (double range : {10.0, 30.0, 42.0}) {
    const io::LabelledScan truth = ringScan(64, range, 71);
    int missed = 0, total = 0;
    for (int k = 0; k < 40; ++k) {
      const io::LabelledScan out = emulator::emulateLidarLabels(truth, p, emulator::detectionSeed(1, 0, k));
      ASSERT_EQ(out.instance.size(), truth.size());
      for (auto id : out.instance) ASSERT_EQ(id, 0) << "the emulator must publish no instance ids";
      for (const auto& [id, l] : majority(truth, out)) missed += l == 70, ++total;
    }
    const double expected = p.classes[0].missProbability(range, 120);
    SCOPED_TRACE(range);
    EXPECT_NEAR(double(missed) / total, expected, 0.04);
  }
  // Objects with fewer points than miss_min_points are always missed.
  p.classes[0].miss_min_points = 200;
  const io::LabelledScan truth = ringScan(16, 10.0, 71);
  for (const auto& [id, l] : majority(truth, emulator::emulateLidarLabels(truth, p, 3))) EXPECT_EQ(l, 70);
}

TEST(LidarEmulator, ConfusionBleedingAndFalsePositivesMatchConfig) {
  emulator::LidarEmulatorParams p;
  emulator::LidarClassErrors e = trunkErrors();
  e.miss_near = 0.0;
  e.miss_range = 1e6;
  e.confusion = {{80, 0.2}};
  p.classes.push_back(e);
  const io::LabelledScan truth = ringScan(64, 10.0, 71);
  int confused = 0, total = 0;
  for (int k = 0; k < 40; ++k)
    for (const auto& [id, l] :
         majority(truth, emulator::emulateLidarLabels(truth, p, emulator::detectionSeed(2, 0, k))))
      confused += l == 80, ++total;
  EXPECT_NEAR(double(confused) / total, 0.2, 0.04);

  // Bleeding: a boundary point (object column next to background) leaves with bleed_out; a
  // background point next to the object joins with bleed_in; interior points never change.
  p.classes[0].confusion.clear();
  p.classes[0].bleed_out = 0.3;
  p.classes[0].bleed_in = 0.5;
  long edge = 0, edge_left = 0, halo = 0, halo_joined = 0, inner_changed = 0;
  for (int k = 0; k < 10; ++k) {
    const io::LabelledScan out = emulator::emulateLidarLabels(truth, p, emulator::detectionSeed(3, 0, k));
    for (std::size_t i = 0; i < truth.size(); ++i) {
      const int c = static_cast<int>(i / 64), r = static_cast<int>(i % 64), within = c % 16;
      if (r < 21 || r > 38) continue;  // rows with object pixels left and right only
      if (truth.semantic[i] == 71 && (within == 0 || within == 5)) ++edge, edge_left += out.semantic[i] != 71;
      if (truth.semantic[i] == 71 && within >= 1 && within <= 4) inner_changed += out.semantic[i] != 71;
      if (truth.semantic[i] == 70 && (within == 6 || within == 15)) ++halo, halo_joined += out.semantic[i] == 71;
    }
  }
  EXPECT_EQ(inner_changed, 0);
  EXPECT_NEAR(double(edge_left) / edge, 0.3, 0.05);
  EXPECT_NEAR(double(halo_joined) / halo, 0.5, 0.05);

  // False-positive patches: Poisson mean per_scan patches of `from` labelled `to`.
  p.classes[0].bleed_out = p.classes[0].bleed_in = 0;
  p.false_positives.push_back({70, 81, 2.0, 1, 10.0});
  long patches = 0;
  const int scans = 100;
  for (int k = 0; k < scans; ++k) {
    const io::LabelledScan out = emulator::emulateLidarLabels(truth, p, emulator::detectionSeed(4, 0, k));
    long fp_points = 0;
    for (std::size_t i = 0; i < out.size(); ++i) fp_points += out.semantic[i] == 81;
    patches += std::lround(fp_points / 5.0);  // a radius-1 patch inside the background: 5 pixels
  }
  EXPECT_NEAR(double(patches) / scans, 2.0, 0.4);
}

TEST(LidarEmulator, DeterministicPerSeed) {
  emulator::LidarEmulatorParams p;
  emulator::LidarClassErrors e = trunkErrors();
  e.bleed_out = e.bleed_in = 0.3;
  e.point_noise = 0.05;
  p.classes.push_back(e);
  const io::LabelledScan truth = ringScan(32, 25.0, 71);
  EXPECT_EQ(emulator::emulateLidarLabels(truth, p, 11).semantic, emulator::emulateLidarLabels(truth, p, 11).semantic);
  EXPECT_NE(emulator::emulateLidarLabels(truth, p, 11).semantic, emulator::emulateLidarLabels(truth, p, 12).semantic);
  io::LabelledScan unlabelled;
  unlabelled.xyz = truth.xyz;
  EXPECT_FALSE(emulator::emulateLidarLabels(unlabelled, p, 1).hasLabels());
}

namespace {
// A 640 x 480 frame with a wall at 10 m and `n` square chairs (class 1) of side `side` pixels
// at depth `depth` in a row.
io::InstanceMask squares(int n, int side, double depth, cv::Mat& depth_img) {
  io::InstanceMask m;
  m.mask = cv::Mat::zeros(480, 640, CV_16UC1);
  depth_img = cv::Mat(480, 640, CV_16UC1, cv::Scalar(10000));
  for (int k = 0; k < n; ++k) {
    const cv::Rect r(10 + (k % 8) * 78, 20 + (k / 8) * 90, side, side);
    m.mask(r).setTo(k + 1);
    depth_img(r).setTo(static_cast<int>(depth * 1000));
    m.class_id.push_back(1);
    m.object_id.push_back(k + 1);
  }
  return m;
}

emulator::RgbdClassErrors chairErrors() {
  emulator::RgbdClassErrors c;
  c.class_id = 1;
  c.detect_max = 0.95;
  c.detect_range = 6.0;
  c.detect_width = 1.0;
  return c;
}
}  // namespace

TEST(RgbdEmulator, MissRateFollowsDepthAndOcclusion) {
  emulator::RgbdEmulatorParams p;
  p.classes.push_back(chairErrors());
  for (double depth : {3.0, 6.0, 7.5}) {
    cv::Mat d;
    const io::InstanceMask truth = squares(40, 60, depth, d);
    int found = 0, total = 0;
    for (int k = 0; k < 30; ++k) {
      const emulator::EmulatedMasks e =
          emulator::emulateRgbdDetections(truth, d, 0.001, p, emulator::detectionSeed(5, 0, k));
      found += static_cast<int>(e.masks.class_id.size()), total += 40;
      for (float c : e.confidence) EXPECT_TRUE(c >= p.score_threshold && c <= 0.99f);
      for (int o : e.masks.object_id) EXPECT_EQ(o, 0);
    }
    SCOPED_TRACE(depth);
    EXPECT_NEAR(double(found) / total, p.classes[0].detectProbability(depth, 0.0), 0.04);
  }
  // Occlusion: a nearer strip over the right half of every square's border.
  p.classes[0].occlusion_weight = 0.8;
  cv::Mat d;
  io::InstanceMask truth = squares(40, 60, 3.0, d);
  for (int k = 0; k < 40; ++k) {
    const cv::Rect r(10 + (k % 8) * 78 + 60, 20 + (k / 8) * 90, 8, 60);
    d(r).setTo(1000);  // 1 m: in front of the chair
  }
  int found = 0;
  for (int k = 0; k < 30; ++k)
    found += static_cast<int>(
        emulator::emulateRgbdDetections(truth, d, 0.001, p, emulator::detectionSeed(6, 0, k)).masks.class_id.size());
  // Occluded boundary fraction: the right edge, 60 of the 236 boundary pixels.
  EXPECT_NEAR(found / 1200.0, p.classes[0].detectProbability(3.0, 60.0 / 236.0), 0.04);
}

TEST(RgbdEmulator, BoundariesConfusionAndFalsePositives) {
  emulator::RgbdEmulatorParams p;
  emulator::RgbdClassErrors c = chairErrors();
  c.detect_max = 1.0;
  c.detect_range = 1e6;
  c.boundary_px = 3;
  c.confusion = {{2, 0.25}};
  p.classes.push_back(c);
  cv::Mat d;
  const io::InstanceMask truth = squares(40, 60, 3.0, d);
  int confused = 0, total = 0, grown = 0, shrunk = 0;
  for (int k = 0; k < 20; ++k) {
    const emulator::EmulatedMasks e =
        emulator::emulateRgbdDetections(truth, d, 0.001, p, emulator::detectionSeed(7, 0, k));
    ASSERT_EQ(e.masks.class_id.size(), 40u);
    for (std::size_t i = 0; i < 40; ++i) {
      confused += e.masks.class_id[i] == 2, ++total;
      const int area = cv::countNonZero(e.masks.mask == static_cast<int>(i + 1));
      EXPECT_GE(area, 54 * 54 - 40);  // eroded by at most 3 pixels ...
      EXPECT_LE(area, 66 * 66);       // ... dilated by at most 3
      grown += area > 3600, shrunk += area < 3600;
    }
  }
  EXPECT_NEAR(double(confused) / total, 0.25, 0.05);
  EXPECT_NEAR(double(grown) / total, 3.0 / 7.0, 0.08);
  EXPECT_NEAR(double(shrunk) / total, 3.0 / 7.0, 0.08);

  // False positives: Poisson per frame on surfaces, below the configured confidence cap.
  p.classes.clear();
  p.false_positives_per_frame = 1.5;
  p.false_positive_classes = {3};
  p.false_positive_radius_px = 20;
  long fps = 0;
  for (int k = 0; k < 200; ++k) {
    const emulator::EmulatedMasks e =
        emulator::emulateRgbdDetections(truth, d, 0.001, p, emulator::detectionSeed(8, 0, k));
    fps += static_cast<long>(e.masks.class_id.size());
    for (std::size_t i = 0; i < e.confidence.size(); ++i) {
      EXPECT_EQ(e.masks.class_id[i], 3);
      EXPECT_LE(e.confidence[i], p.false_positive_max_confidence + 1e-6);
    }
  }
  EXPECT_NEAR(fps / 200.0, 1.5, 0.25);  // centres on the depth-discontinuous chairs' edges may fall short of min_area
}

TEST(DetectionEmulatorConfig, ShippedConfigLoadsAndBadValuesNameTheKey) {
  const emulator::DetectionEmulatorConfig c =
      emulator::loadDetectionEmulatorConfig(std::string(SLIDE_SOURCE_DIR) + "/config/detections.yaml");
  ASSERT_TRUE(c.lidar.find(10) && c.lidar.find(71) && c.lidar.find(80));
  EXPECT_TRUE(c.rgbd.find(1) && c.rgbd.find(2) && c.rgbd.find(3));
  const std::string bad = (std::filesystem::temp_directory_path() / "slide_bad_detections.yaml").string();
  std::ofstream(bad) << "lidar:\n  classes:\n    - {label: 71, bleed_out: 1.5}\n";
  try {
    emulator::loadDetectionEmulatorConfig(bad);
    FAIL() << "expected a ConfigError";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("bleed_out"), std::string::npos) << e.what();
  }
}
