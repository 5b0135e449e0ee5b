// YOLOv8-seg decoding (boxes, class-wise NMS, masks from prototypes, letterbox geometry) on
// hand-made outputs, and the detector through OpenCV DNN on a small committed ONNX fixture
// (tests/data/models/make_fixtures.py) with known outputs, plus its failures at load.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>

#include "error_text.h"
#include "frontend/yolo_seg_decoder.h"
#include "frontend/yolo_seg_detector.h"

using namespace slide;

namespace {
const std::string kModels = std::string(SLIDE_SOURCE_DIR) + "/tests/data/models/";

// output0 [1, 4 + 2 + 32, anchors] from rows of (cx, cy, w, h, score0, score1, coefficient 0).
cv::Mat outputs0(const std::vector<std::array<float, 7>>& anchors) {
  const int n = static_cast<int>(anchors.size()), dims[3] = {1, 38, n};
  cv::Mat m(3, dims, CV_32F, cv::Scalar(0));
  float* d = m.ptr<float>();
  for (int a = 0; a < n; ++a)
    for (int r = 0; r < 7; ++r) d[r * n + a] = anchors[a][r];
  return m;
}

// output1 [1, 32, 8, 8]: prototype 0 is +10 on the left half, -10 on the right half.
cv::Mat halves() {
  const int dims[4] = {1, 32, 8, 8};
  cv::Mat m(4, dims, CV_32F, cv::Scalar(0));
  float* d = m.ptr<float>();
  for (int v = 0; v < 8; ++v)
    for (int u = 0; u < 8; ++u) d[v * 8 + u] = u < 4 ? 10.0f : -10.0f;
  return m;
}

using slide::test::errorText;

int count(const cv::Mat& m) { return cv::countNonZero(m); }
}  // namespace

TEST(YoloSeg, LetterboxScalesCentresAndPads) {
  const frontend::Letterbox a = frontend::letterboxOf(640, 480, 640, 640);
  EXPECT_DOUBLE_EQ(a.scale, 1.0);
  EXPECT_EQ(a.pad_x, 0);
  EXPECT_EQ(a.pad_y, 80);
  EXPECT_EQ(a.height, 480);
  const frontend::Letterbox b = frontend::letterboxOf(64, 32, 32, 32);
  EXPECT_DOUBLE_EQ(b.scale, 0.5);
  EXPECT_EQ(b.width, 32);
  EXPECT_EQ(b.height, 16);
  EXPECT_EQ(b.pad_y, 8);
  const cv::Mat img = frontend::letterboxImage(cv::Mat(32, 64, CV_8UC3, cv::Scalar(1, 2, 3)), b, 32, 32);
  EXPECT_EQ(img.at<cv::Vec3b>(0, 0), cv::Vec3b(114, 114, 114));
  EXPECT_EQ(img.at<cv::Vec3b>(8, 0), cv::Vec3b(1, 2, 3));
  EXPECT_EQ(img.at<cv::Vec3b>(24, 31), cv::Vec3b(114, 114, 114));
  EXPECT_THROW(frontend::letterboxOf(0, 1, 1, 1), std::invalid_argument);
}

TEST(YoloSeg, DecodesBoxesAndSuppressesOverlapsWithinAClass) {
  frontend::YoloSegParams p;
  p.input_width = p.input_height = 32;
  const cv::Mat out0 = outputs0({
      {10, 10, 8, 8, 0.9f, 0.0f, 1},    // A: class 0
      {11, 10, 8, 8, 0.8f, 0.1f, 1},    // B: overlaps A (IoU 0.78) in class 0: suppressed
      {10, 10, 8, 8, 0.0f, 0.7f, 1},    // C: A's box, class 1: kept
      {24, 24, 8, 8, 0.2f, 0.1f, -1},   // D: below the score threshold
      {24, 24, 8, 8, 0.6f, 0.0f, -1},   // E: apart, class 0: kept
  });
  const auto inst = frontend::decodeYoloSeg(out0, halves(), 2, frontend::letterboxOf(32, 32, 32, 32), 32, 32, p);
  ASSERT_EQ(inst.size(), 3u);
  EXPECT_EQ(inst[0].model_class, 0);
  EXPECT_FLOAT_EQ(inst[0].score, 0.9f);
  EXPECT_EQ(inst[0].box, cv::Rect2d(6, 6, 8, 8));
  EXPECT_EQ(inst[1].model_class, 1);
  EXPECT_FLOAT_EQ(inst[1].score, 0.7f);
  EXPECT_EQ(inst[2].box, cv::Rect2d(20, 20, 8, 8));
  // Masks: the prototype's left half (upsampled 8 -> 32: columns 0-15) within A's box, its
  // right half (coefficient -1) within E's.
  EXPECT_EQ(count(inst[0].mask), 64);
  EXPECT_EQ(count(inst[0].mask(cv::Rect(6, 6, 8, 8))), 64);
  EXPECT_EQ(count(inst[2].mask), 64);
  EXPECT_EQ(count(inst[2].mask(cv::Rect(20, 20, 8, 8))), 64);
  p.nms_iou = 0.8;  // B's overlap no longer suppresses it
  EXPECT_EQ(frontend::decodeYoloSeg(out0, halves(), 2, frontend::letterboxOf(32, 32, 32, 32), 32, 32, p).size(), 4u);
  p.max_detections = 1;
  EXPECT_EQ(frontend::decodeYoloSeg(out0, halves(), 2, frontend::letterboxOf(32, 32, 32, 32), 32, 32, p).size(), 1u);
}

TEST(YoloSeg, MaskIsCutToItsBoxAndTheMaskEdgeInImagePixels) {
  frontend::YoloSegParams p;
  p.input_width = p.input_height = 32;
  // A box over both halves: only its left part (columns < 16) is mask.
  const auto inst = frontend::decodeYoloSeg(outputs0({{16, 16, 16, 4, 0.9f, 0, 1}}), halves(), 2,
                                            frontend::letterboxOf(32, 32, 32, 32), 32, 32, p);
  ASSERT_EQ(inst.size(), 1u);
  EXPECT_EQ(count(inst[0].mask), 8 * 4);
  EXPECT_EQ(count(inst[0].mask(cv::Rect(8, 14, 8, 4))), 8 * 4);
}

TEST(YoloSeg, WrongOutputShapesNameWhatWasExpected) {
  frontend::YoloSegParams p;
  const int bad0[3] = {1, 37, 5}, bad1[3] = {1, 32, 64};
  const std::string a = errorText([&] {
    frontend::decodeYoloSeg(cv::Mat(3, bad0, CV_32F, cv::Scalar(0)), halves(), 2, frontend::letterboxOf(32, 32, 32, 32),
                            32, 32, p);
  });
  EXPECT_NE(a.find("output0 [1, 37, 5]: expected float [1, 38 (4 box + 2 classes + 32 mask coefficients), anchors]"),
            std::string::npos) << a;
  const std::string b = errorText([&] {
    frontend::decodeYoloSeg(outputs0({}), cv::Mat(3, bad1, CV_32F, cv::Scalar(0)), 2,
                            frontend::letterboxOf(32, 32, 32, 32), 32, 32, p);
  });
  EXPECT_NE(b.find("output1 [1, 32, 64]: expected float [1, 32, mask height, mask width]"), std::string::npos) << b;
}

// The fixture: every anchor is the box (cx 16, cy 12, w 16, h 8) of class 1 ("car") with score
// 0.9 and a mask covering it. A 64 x 32 image is letterboxed at scale 0.5 with 8 rows of padding
// above: the box is columns 16-47, rows 0-15 of the image.
TEST(YoloSegDetector, RunsTheModelAndMapsClassesAndMasksToTheImage) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::YoloSegDetector det(frontend::loadYoloSegConfig(kModels + "yolo_seg.yaml", classes));
  frontend::RgbdFrame f;
  f.intrinsics.width = 64, f.intrinsics.height = 32;
  f.color.assign(64 * 32 * 3, 50);
  det.detect(f);
  ASSERT_EQ(f.instance_class.size(), 1u);
  EXPECT_EQ(f.instance_class[0], classes.findByName("car")->id);
  EXPECT_FLOAT_EQ(f.instance_confidence[0], 0.9f);
  ASSERT_EQ(f.mask.size(), 64u * 32u);
  int inside = 0, outside = 0;
  for (int v = 0; v < 32; ++v)
    for (int u = 0; u < 64; ++u) (u >= 16 && u < 48 && v < 16 ? inside : outside) += f.mask[v * 64 + u] == 1;
  EXPECT_EQ(inside, 32 * 16);
  EXPECT_EQ(outside, 0);
  frontend::RgbdFrame no_colour;
  no_colour.intrinsics.width = 4, no_colour.intrinsics.height = 4;
  det.detect(no_colour);
  EXPECT_TRUE(no_colour.instance_class.empty());
  EXPECT_EQ(no_colour.mask.size(), 16u);
}

TEST(YoloSegDetector, BadModelsAndConfigsFailAtLoad) {
  const ClassTable classes = ClassTable::loadDefault();
  const std::string shape =
      errorText([&] { frontend::YoloSegDetector(frontend::loadYoloSegConfig(kModels + "yolo_seg_37.yaml", classes)); });
  EXPECT_NE(shape.find("yolo_seg_37.onnx: YOLOv8-seg output0 [1, 37, 16]: expected float [1, 38"), std::string::npos) << shape;
  EXPECT_NE(shape.find("2 classes in"), std::string::npos) << shape;
  frontend::YoloSegConfig missing = frontend::loadYoloSegConfig(kModels + "yolo_seg.yaml", classes);
  missing.model_path = kModels + "nowhere.onnx";
  EXPECT_NE(errorText([&] { frontend::YoloSegDetector{missing}; }).find("nowhere.onnx: no such model file"),
            std::string::npos);
  frontend::YoloSegConfig corrupt = missing;
  corrupt.model_path = kModels + "corrupt.onnx";
  EXPECT_NE(errorText([&] { frontend::YoloSegDetector{corrupt}; }).find("corrupt.onnx: not a readable ONNX model"),
            std::string::npos);
  const std::string path = testing::TempDir() + "/yolo_bad.yaml";
  std::ofstream(path) << "model: m.onnx\ninput: {width: 32, height: 32}\nclasses: [{name: x, class: spaceship}]\n";
  const std::string cls = errorText([&] { frontend::loadYoloSegConfig(path, classes); });
  EXPECT_NE(cls.find("no class named 'spaceship'"), std::string::npos) << cls;
  EXPECT_NE(cls.find("yolo_bad.yaml"), std::string::npos) << cls;
}
