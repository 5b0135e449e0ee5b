// The segmenter's and the tracker's nodes chained without a bus: odometry and labelled scans in,
// per-frame instances out of the segmenter into the tracker, key-pose bundles out of the tracker
// through the injected publishers. A scan waits for its odometry; bad input is skipped and
// counted, never published.
#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <limits>
#include <map>

#include "frontend/frontend_config.h"
#include "drive_by.h"
#include "msg/frontend_convert.h"
#include "segmenter_node.h"
#include "synthetic_scene.h"
#include "tracker_node.h"

using namespace slide;
using namespace slide::testing;

namespace {
template <typename M>
M decoded(const std::vector<uint8_t>& bytes) {
  M m;
  EXPECT_EQ(m.decode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  return m;
}
}  // namespace

TEST(FrontendNodes, ScansBecomeInstancesAndKeyPoseBundles) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg =
      frontend::loadFrontendConfig(std::string(SLIDE_SOURCE_DIR) + "/config/frontend.yaml");
  std::vector<keypose_bundle_t> bundles;
  TrackerNode tracker(0, "KEYPOSE_BUNDLE", classes, cfg, [&](const std::string& c, const std::vector<uint8_t>& b) {
    EXPECT_EQ(c, "KEYPOSE_BUNDLE");
    bundles.push_back(decoded<keypose_bundle_t>(b));
    return true;
  });
  int instances = 0;
  SegmenterNode segmenter(0, "INSTANCES", classes, cfg, 50, [&](const std::string& c, const std::vector<uint8_t>& b) {
    EXPECT_EQ(c, "INSTANCES");
    ++instances;
    tracker.onInstances(decoded<frame_instances_t>(b));
    return true;
  });

  const std::vector<synth::SceneObject> scene{{71, {6, 4, 0}, 0.25, 6.0}, {71, {12, -4, 0}, 0.35, 6.0}};
  const int frames = 12;
  for (int k = 0; k < frames; ++k) {
    // The scan comes before the odometry at its time: it waits for it. Frame 5 is empty.
    const io::LabelledScan scan =
        k == 5 ? io::LabelledScan{} : synth::syntheticScan(scene, driveByPose(k), 0.08, k + 1, 0.01, 0.6);
    segmenter.onScan(msg::toLcm(scan, driveByHeader(k)));
    if (k == 0) {
      EXPECT_EQ(segmenter.published(), 0);
    }
    segmenter.onOdom(driveByOdometry(k));
  }
  segmenter.onOdom(driveByOdometry(frames));
  EXPECT_EQ(instances, frames - 1);  // the empty scan gives none
  EXPECT_EQ(segmenter.published(), frames - 1);
  EXPECT_EQ(segmenter.issues().total(), 1);
  ASSERT_GE(bundles.size(), 3u);  // ~4.4 m driven, a key pose per metre
  for (std::size_t i = 0; i < bundles.size(); ++i) {
    EXPECT_EQ(bundles[i].header.seq, static_cast<int>(i));
    EXPECT_EQ(bundles[i].header.robot, 0);
  }
  EXPECT_EQ(tracker.bundles(), static_cast<int>(bundles.size()));

  frame_instances_t other{};  // another robot's instances: skipped and counted
  other.header.robot = 1;
  tracker.onInstances(other);
  EXPECT_EQ(tracker.issues().total(), 1);
  EXPECT_EQ(tracker.bundles(), static_cast<int>(bundles.size()));
}

// lidar_mode learned: the model (the fixture tests/data/models/range3: points nearer than 9 m
// are "car", farther than 11 m "vegetation") labels the points; the labelled segmenter makes
// the car cluster one car instance, vegetation no object. The scan's own labels are ignored.
TEST(FrontendNodes, LearnedModeSegmentsTheModelsLabels) {
  const ClassTable classes = ClassTable::loadDefault();
  frontend::FrontendConfig cfg = frontend::loadFrontendConfig(std::string(SLIDE_SOURCE_DIR) + "/config/frontend.yaml");
  cfg.lidar_mode = "learned";
  cfg.learned = frontend::LearnedLidarParams{};
  cfg.learned.model = std::string(SLIDE_SOURCE_DIR) + "/tests/data/models/range3.yaml";
  cfg.learned.width = 512;
  std::vector<frame_instances_t> out;
  SegmenterNode segmenter(0, "INSTANCES", classes, cfg, 50, [&](const std::string&, const std::vector<uint8_t>& b) {
    out.push_back(decoded<frame_instances_t>(b));
    return true;
  });
  io::LabelledScan scan;
  for (int i = 0; i < 20; ++i)      // a car-sized block of returns 5 m ahead ...
    for (int j = 0; j < 15; ++j) scan.xyz.emplace_back(5.0f + 0.1f * (i % 3), -1.0f + 0.1f * i, -1.2f + 0.1f * j);
  for (int i = 0; i < 200; ++i)     // ... and a hedge 15 m to the left
    scan.xyz.emplace_back(0.05f * i - 5, 15.0f, -1.0f + 0.01f * (i % 100));
  scan.intensity.assign(scan.size(), 0.5f);
  scan.semantic.assign(scan.size(), 71);  // labels on the bus (oracle): not used in learned mode
  scan.instance.assign(scan.size(), 0);
  segmenter.onScan(msg::toLcm(scan, driveByHeader(0)));
  segmenter.onOdom(driveByOdometry(0));
  segmenter.onOdom(driveByOdometry(1));
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].instances.size(), 1u);
  EXPECT_EQ(out[0].instances[0].class_id, classes.findByName("car")->id);
  EXPECT_EQ(out[0].instances[0].num_points, 300);

  cfg.learned.model = std::string(SLIDE_SOURCE_DIR) + "/tests/data/models/missing.yaml";
  try {
    SegmenterNode bad(0, "INSTANCES", classes, cfg, 50, [](const std::string&, const std::vector<uint8_t>&) { return true; });
    FAIL() << "a missing model must fail at start";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.onnx: no such model file"), std::string::npos) << e.what();
  }
}

namespace {
// A 64 x 32 RGBD frame without masks, of colour colour(u, v) (BGR) and depth depth_mm(u, v),
// through a segmenter whose segmenter.rgbd.detector is the fixture `model_yaml`: what it publishes.
std::vector<frame_instances_t> segmentWithDetector(const ClassTable& classes, const std::string& model_yaml,
                                                   const std::function<std::array<uint8_t, 3>(int, int)>& colour,
                                                   const std::function<int(int, int)>& depth_mm) {
  frontend::FrontendConfig cfg = frontend::loadFrontendConfig(std::string(SLIDE_SOURCE_DIR) + "/config/frontend.yaml");
  cfg.rgbd_detector = std::string(SLIDE_SOURCE_DIR) + "/tests/data/models/" + model_yaml;
  cfg.rgbd.erode_px = 0;
  std::vector<frame_instances_t> out;
  SegmenterNode segmenter(0, "INSTANCES", classes, cfg, 50, [&](const std::string&, const std::vector<uint8_t>& b) {
    out.push_back(decoded<frame_instances_t>(b));
    return true;
  });
  rgbd_frame_t m{};
  m.header = driveByHeader(0);
  m.intrinsics = {64, 32, 40.0, 40.0, 32.0, 16.0, 0.001};
  for (int v = 0; v < 32; ++v)
    for (int u = 0; u < 64; ++u) {
      for (uint8_t c : colour(u, v)) m.color.push_back(c);
      const int mm = depth_mm(u, v);
      m.depth.push_back(mm & 0xff), m.depth.push_back(mm >> 8);
    }
  m.color_size = static_cast<int>(m.color.size());
  m.depth_size = static_cast<int>(m.depth.size());
  m.mask_size = 0;  // no masks on the bus
  m.num_instances = 0;
  segmenter.onRgbd(m);
  segmenter.onOdom(driveByOdometry(0));
  segmenter.onOdom(driveByOdometry(1));
  return out;
}
}  // namespace

// segmenter.rgbd.detector: the segmenter takes the masks from the colour image through the
// YOLOv8-seg model (the fixture tests/data/models/yolo_seg: one "car" box, columns 16-47 and
// rows 0-15 of a 64 x 32 image), not from the frame, and back-projects them with the depth.
TEST(FrontendNodes, RgbdDetectorMasksTheColourImage) {
  const ClassTable classes = ClassTable::loadDefault();
  const auto out = segmentWithDetector(
      classes, "yolo_seg.yaml", [](int, int) { return std::array<uint8_t, 3>{80, 80, 80}; }, [](int, int) { return 2000; });
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].instances.size(), 1u);
  EXPECT_EQ(out[0].instances[0].class_id, classes.findByName("car")->id);
  EXPECT_EQ(out[0].instances[0].num_points, 32 * 16);
}

// segmenter.rgbd.detector naming a `type: semantic` model YAML: the segmenter builds the
// per-pixel detector (the fixture tests/data/models/semantic: red -> chair, blue -> car) and
// splits its classes into instances by depth: the red top half of the image, its left and
// right quarters 1 m apart, is two chairs.
TEST(FrontendNodes, RgbdSemanticDetectorSplitsClassesByDepth) {
  const ClassTable classes = ClassTable::loadDefault();
  const auto out = segmentWithDetector(
      classes, "semantic.yaml",
      [](int, int v) { return std::array<uint8_t, 3>{0, 0, static_cast<uint8_t>(v < 16 ? 255 : 0)}; },
      [](int u, int v) { return v < 16 && u >= 32 ? 3000 : 2000; });
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].instances.size(), 2u);
  for (const auto& inst : out[0].instances) {
    EXPECT_EQ(inst.class_id, classes.findByName("chair")->id);
    EXPECT_EQ(inst.num_points, 32 * 16);
  }
}

// The preview (setPreview): a thinned copy of the published frames, at most one per period of
// frame time and at most max_points points, each instance keeping its class and id; none
// without a preview channel.
TEST(FrontendNodes, PreviewIsAThinnedCopyOfAFrameEveryPeriod) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg =
      frontend::loadFrontendConfig(std::string(SLIDE_SOURCE_DIR) + "/config/frontend.yaml");
  std::map<int, frame_instances_t> full, preview;  // by seq
  SegmenterNode segmenter(0, "INSTANCES", classes, cfg, 50, [&](const std::string& c, const std::vector<uint8_t>& b) {
    const auto m = decoded<frame_instances_t>(b);
    (c == "INSTANCES" ? full : preview)[m.header.seq] = m;
    EXPECT_TRUE(c == "INSTANCES" || c == "INSTANCES_PREVIEW") << c;
    return true;
  });
  segmenter.setPreview({"INSTANCES_PREVIEW", 0.25, 40});
  const std::vector<synth::SceneObject> scene{{71, {6, 4, 0}, 0.25, 6.0}, {71, {12, -4, 0}, 0.35, 6.0}};
  for (int k = 0; k < 12; ++k) {  // frames 0.1 s apart
    segmenter.onScan(msg::toLcm(synth::syntheticScan(scene, driveByPose(k), 0.08, k + 1, 0.01, 0.6), driveByHeader(k)));
    segmenter.onOdom(driveByOdometry(k));
  }
  segmenter.onOdom(driveByOdometry(12));
  ASSERT_EQ(full.size(), 12u);
  std::vector<int> seqs;
  for (const auto& [seq, m] : preview) seqs.push_back(seq);
  EXPECT_EQ(seqs, (std::vector<int>{0, 3, 6, 9}));  // frame time 0, 0.3, 0.6, 0.9 s
  EXPECT_EQ(segmenter.previews(), 4);
  for (const auto& [seq, m] : preview) {
    const frame_instances_t& f = full.at(seq);
    int points = 0, full_points = 0;
    for (const auto& i : m.instances) points += i.num_points;
    for (const auto& i : f.instances) full_points += i.num_points;
    EXPECT_GT(full_points, 40);
    EXPECT_LE(points, 40);
    EXPECT_GT(points, 0);
    ASSERT_EQ(m.num_instances, f.num_instances);
    for (int i = 0; i < m.num_instances; ++i) {
      EXPECT_EQ(m.instances[i].class_id, f.instances[i].class_id);
      EXPECT_EQ(m.instances[i].instance_id, f.instances[i].instance_id);
    }
    for (int a = 0; a < 3; ++a) EXPECT_DOUBLE_EQ(m.odom_pose.position[a], f.odom_pose.position[a]);
  }
}

// The cells a car's box is not completed over travel with its instance from the segmenter to the
// tracker: on their 0.2 m grid the bus's 0.1 m units keep them exactly; a non-finite height drops
// them (the points stay).
TEST(FrontendNodes, FreeCellsTravelWithTheirInstance) {
  frontend::FrameInstances f;
  frontend::Instance inst;
  inst.id = 1, inst.class_id = 10;
  inst.points = {Eigen::Vector3f(8, 1, 0), Eigen::Vector3f(8, 2, 0.5f)};
  inst.free_space = {Eigen::Vector3f(7.9f, 0.3f, -0.9f), Eigen::Vector3f(-12.1f, 3.5f, -0.9f)};
  f.instances = {inst};
  header_t h{};
  const frontend::FrameInstances back = msg::fromLcm(decoded<frame_instances_t>([&] {
    const frame_instances_t m = msg::toLcm(f, h);
    std::vector<uint8_t> bytes(m.getEncodedSize());
    m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    return bytes;
  }()));
  ASSERT_EQ(back.instances.size(), 1u);
  ASSERT_EQ(back.instances[0].free_space.size(), 2u);
  for (int k = 0; k < 2; ++k) EXPECT_LT((back.instances[0].free_space[k] - inst.free_space[k]).norm(), 1e-5f);

  frame_instances_t hostile = msg::toLcm(f, h);
  hostile.instances[0].free_z = std::numeric_limits<float>::quiet_NaN();
  const frontend::FrameInstances dropped = msg::fromLcm(hostile);
  EXPECT_TRUE(dropped.instances[0].free_space.empty());
  EXPECT_EQ(dropped.instances[0].points.size(), 2u);
}
