// Per-pixel semantic decoding (classes and probabilities per pixel, nearest-neighbour
// upsampling, depth-aware connected components, painting into the frame) on hand-made scores,
// and the detector through OpenCV DNN on a small committed ONNX fixture
// (tests/data/models/make_fixtures.py) with known outputs, its failures at load, and the
// choice of detector by the model YAML's type.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>

#include "config/config.h"
#include "error_text.h"
#include "frontend/mask_detector_loader.h"
#include "frontend/semantic_seg_decoder.h"
#include "frontend/semantic_seg_detector.h"

using namespace slide;
using slide::test::errorText;

namespace {
const std::string kModels = std::string(SLIDE_SOURCE_DIR) + "/tests/data/models/";

// Scores [1, k, h, w] with score(c, v, u) at each class, row and column.
cv::Mat scoresOf(int k, int h, int w, const std::function<float(int, int, int)>& score) {
  const int dims[4] = {1, k, h, w};
  cv::Mat m(4, dims, CV_32F);
  float* d = m.ptr<float>();
  for (int c = 0; c < k; ++c)
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) d[(c * h + v) * w + u] = score(c, v, u);
  return m;
}

// Two classes as probabilities: class 1 with `p` where `one(v, u)`, else class 0 with `p`.
cv::Mat twoClasses(int h, int w, float p, const std::function<bool(int, int)>& one) {
  return scoresOf(2, h, w, [&](int c, int v, int u) { return (c == 1) == one(v, u) ? p : 1.0f - p; });
}

frontend::SemanticSegParams probabilities(int min_pixels = 1) {
  frontend::SemanticSegParams p;
  p.logits = false;
  p.min_pixels = min_pixels;
  return p;
}

// Depth image (mm) of width w from depth_mm(v, u).
std::vector<std::uint16_t> depthOf(int h, int w, const std::function<int(int, int)>& depth_mm) {
  std::vector<std::uint16_t> d;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) d.push_back(static_cast<std::uint16_t>(depth_mm(v, u)));
  return d;
}

std::vector<frontend::SemanticInstance> components(const cv::Mat& scores, int k, int h, int w,
                                                   const std::vector<std::uint16_t>& depth,
                                                   const frontend::SemanticSegParams& p) {
  return frontend::depthComponents(frontend::classifyPixels(scores, k, w, h, p), depth, 0.001, p);
}

std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}
}  // namespace

TEST(SemanticSeg, TouchingObjectsOfOneClassAtDifferentDepthsAreTwoInstances) {
  const cv::Mat s = twoClasses(4, 8, 0.9f, [](int, int) { return true; });
  // Columns 0-3 at 2 m, 4-7 at 2.5 m: touching in the image, 0.5 m apart.
  const auto two = components(s, 2, 4, 8, depthOf(4, 8, [](int, int u) { return u < 4 ? 2000 : 2500; }), probabilities());
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].pixels.size(), 16u);
  EXPECT_EQ(two[1].pixels.size(), 16u);
  EXPECT_EQ(sorted(two[0].pixels).front(), 0);
  EXPECT_EQ(sorted(two[1].pixels).front(), 4);
  EXPECT_EQ(two[0].model_class, 1);
  EXPECT_FLOAT_EQ(two[0].confidence, 0.9f);
  // The same at one depth (and within the 0.10 m step): one instance.
  EXPECT_EQ(components(s, 2, 4, 8, depthOf(4, 8, [](int, int) { return 2000; }), probabilities()).size(), 1u);
  const auto one = components(s, 2, 4, 8, depthOf(4, 8, [](int, int u) { return u < 4 ? 2000 : 2090; }), probabilities());
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].pixels.size(), 32u);
}

TEST(SemanticSeg, DepthStepGrowsWithDepthAsAFraction) {
  const cv::Mat s = twoClasses(1, 2, 0.9f, [](int, int) { return true; });
  // 0.15 m apart: more than max(0.10, 0.05 * 2 m) at 2 m, less than 0.05 * 4 m at 4 m.
  EXPECT_EQ(components(s, 2, 1, 2, {2000, 2150}, probabilities()).size(), 2u);
  EXPECT_EQ(components(s, 2, 1, 2, {4000, 4150}, probabilities()).size(), 1u);
  frontend::SemanticSegParams p = probabilities();
  p.depth_step_fraction = 0.0;
  EXPECT_EQ(components(s, 2, 1, 2, {4000, 4150}, p).size(), 2u);
}

TEST(SemanticSeg, ComponentsAreFourConnectedAndOneClassEach) {
  // A diagonal pair of class 1 pixels is two instances; class 0 beside class 1 at one depth
  // stays apart.
  const cv::Mat diag = twoClasses(2, 2, 0.9f, [](int v, int u) { return u == v; });
  const auto inst = components(diag, 2, 2, 2, {2000, 2000, 2000, 2000}, probabilities());
  ASSERT_EQ(inst.size(), 4u);
  int ones = 0;
  for (const auto& i : inst) {
    ones += i.model_class == 1;
    EXPECT_EQ(i.pixels.size(), 1u);
  }
  EXPECT_EQ(ones, 2);
}

TEST(SemanticSeg, PixelsWithoutDepthJoinNoInstance) {
  const cv::Mat s = twoClasses(1, 9, 0.9f, [](int, int) { return true; });
  const auto inst = components(s, 2, 1, 9, {2000, 2000, 2000, 2000, 0, 2000, 2000, 2000, 2000}, probabilities());
  ASSERT_EQ(inst.size(), 2u);
  EXPECT_EQ(sorted(inst[0].pixels), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(sorted(inst[1].pixels), (std::vector<int>{5, 6, 7, 8}));
}

TEST(SemanticSeg, PixelsBelowMinConfidenceStayUnlabelled) {
  // Three classes: the winner, class 1, has 0.4.
  const cv::Mat s = scoresOf(3, 1, 4, [](int c, int, int) { return c == 1 ? 0.4f : 0.3f; });
  frontend::SemanticSegParams p = probabilities();
  const frontend::PixelClasses px = frontend::classifyPixels(s, 3, 4, 1, p);
  EXPECT_EQ(px.model_class, (std::vector<int>{-1, -1, -1, -1}));
  EXPECT_TRUE(frontend::depthComponents(px, {2000, 2000, 2000, 2000}, 0.001, p).empty());
  p.min_confidence = 0.35;
  const frontend::PixelClasses labelled = frontend::classifyPixels(s, 3, 4, 1, p);
  EXPECT_EQ(labelled.model_class, (std::vector<int>{1, 1, 1, 1}));
  EXPECT_FLOAT_EQ(labelled.probability[0], 0.4f);
  EXPECT_EQ(frontend::depthComponents(labelled, {2000, 2000, 2000, 2000}, 0.001, p).size(), 1u);
}

TEST(SemanticSeg, ComponentsBelowMinPixelsAreDropped) {
  // Class 1 in columns 0-2 (3 pixels) and 4-7 (4 pixels), class 0 at column 3.
  const cv::Mat s = twoClasses(1, 8, 0.9f, [](int, int u) { return u != 3; });
  const std::vector<std::uint16_t> depth(8, 2000);
  const auto inst = components(s, 2, 1, 8, depth, probabilities(4));
  ASSERT_EQ(inst.size(), 1u);
  EXPECT_EQ(sorted(inst[0].pixels), (std::vector<int>{4, 5, 6, 7}));
  EXPECT_EQ(components(s, 2, 1, 8, depth, probabilities(3)).size(), 2u);
}

TEST(SemanticSeg, LogitsGoThroughSoftmaxProbabilitiesDoNot) {
  const cv::Mat s = scoresOf(2, 1, 2, [](int c, int, int) { return c == 1 ? 0.6f : 0.0f; });
  const float softmax = static_cast<float>(1.0 / (1.0 + std::exp(-0.6)));  // 0.6457
  frontend::SemanticSegParams logits;
  logits.min_pixels = 1;
  const auto a = components(s, 2, 1, 2, {2000, 2000}, logits);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_NEAR(a[0].confidence, softmax, 1e-6);
  const auto b = components(s, 2, 1, 2, {2000, 2000}, probabilities());
  ASSERT_EQ(b.size(), 1u);
  EXPECT_NEAR(b[0].confidence, 0.6f, 1e-6);
  // A gate between the two: the logits pass, the probabilities do not.
  logits.min_confidence = 0.62;
  frontend::SemanticSegParams probs = probabilities();
  probs.min_confidence = 0.62;
  EXPECT_EQ(components(s, 2, 1, 2, {2000, 2000}, logits).size(), 1u);
  EXPECT_TRUE(components(s, 2, 1, 2, {2000, 2000}, probs).empty());
}

TEST(SemanticSeg, ConfidenceIsTheMeanProbabilityOfTheComponent) {
  const cv::Mat s = scoresOf(2, 1, 2, [](int c, int, int u) { return c == 1 ? (u == 0 ? 0.6f : 0.8f) : 0.1f; });
  const auto inst = components(s, 2, 1, 2, {2000, 2000}, probabilities());
  ASSERT_EQ(inst.size(), 1u);
  EXPECT_NEAR(inst[0].confidence, 0.7f, 1e-6);
}

TEST(SemanticSeg, SmallerOutputsAreUpsampledNearestNeighbour) {
  // Output 4 x 2 for an 8 x 4 image: class 1 at output column 1 -> image columns 2-3; and an
  // image 5 wide reads output columns 0, 0, 1, 1, 1 (pixel centres (u + 0.5) * 2 / 5).
  const cv::Mat s = twoClasses(2, 4, 0.9f, [](int, int u) { return u == 1; });
  const frontend::PixelClasses px = frontend::classifyPixels(s, 2, 8, 4, probabilities());
  for (int v = 0; v < 4; ++v)
    for (int u = 0; u < 8; ++u) EXPECT_EQ(px.model_class[v * 8 + u], u == 2 || u == 3 ? 1 : 0) << u << ", " << v;
  const cv::Mat halves = twoClasses(1, 2, 0.9f, [](int, int u) { return u == 1; });
  EXPECT_EQ(frontend::classifyPixels(halves, 2, 5, 1, probabilities()).model_class, (std::vector<int>{0, 0, 1, 1, 1}));
}

TEST(SemanticSeg, InstancesOfClassesMappedToNoneAreNotPainted) {
  // Class 0 in columns 0-3, class 1 in 4-7; class 0 maps to none.
  const cv::Mat s = twoClasses(1, 8, 0.9f, [](int, int u) { return u >= 4; });
  const auto inst = components(s, 2, 1, 8, std::vector<std::uint16_t>(8, 2000), probabilities());
  ASSERT_EQ(inst.size(), 2u);
  frontend::RgbdFrame f;
  f.intrinsics.width = 8, f.intrinsics.height = 1;
  frontend::paintSemanticInstances(inst, {-1, 7}, f);
  EXPECT_EQ(f.instance_class, (std::vector<int>{7}));
  EXPECT_EQ(f.instance_confidence, (std::vector<float>{0.9f}));
  EXPECT_EQ(f.mask, (std::vector<std::uint16_t>{0, 0, 0, 0, 1, 1, 1, 1}));
}

TEST(SemanticSeg, BadShapesAndSizesAreErrorsNotCrashes) {
  const cv::Mat s = twoClasses(4, 8, 0.9f, [](int, int) { return true; });
  const std::string a = errorText([&] { frontend::classifyPixels(s, 3, 8, 4, probabilities()); });
  EXPECT_NE(a.find("semantic scores [1, 2, 4, 8]: expected float [1, 3 classes, height, width]"), std::string::npos) << a;
  EXPECT_THROW(frontend::classifyPixels(s, 2, 0, 4, probabilities()), std::invalid_argument);
  // A depth image of another size, or no depth scale: no instances.
  const frontend::PixelClasses px = frontend::classifyPixels(s, 2, 8, 4, probabilities());
  EXPECT_TRUE(frontend::depthComponents(px, std::vector<std::uint16_t>(5, 2000), 0.001, probabilities()).empty());
  EXPECT_TRUE(frontend::depthComponents(px, std::vector<std::uint16_t>(32, 2000), 0.0, probabilities()).empty());
}

TEST(SemanticSeg, InputIsResizedSwappedAndNormalisedPerChannel) {
  frontend::SemanticSegConfig c;
  c.input_width = 2, c.input_height = 1;
  c.mean = {1, 2, 3};
  c.stddev = {2, 4, 5};
  const cv::Mat bgr(2, 4, CV_8UC3, cv::Scalar(10, 20, 30));  // B 10, G 20, R 30
  const std::vector<float> rgb = frontend::semanticSegInput(bgr, c);
  EXPECT_EQ(rgb, (std::vector<float>{14.5f, 14.5f, 4.5f, 4.5f, 1.4f, 1.4f}));  // (R - 1) / 2, (G - 2) / 4, (B - 3) / 5
  c.swap_rb = false;
  EXPECT_FLOAT_EQ(frontend::semanticSegInput(bgr, c)[0], 4.5f);  // (B - 1) / 2
}

// The fixture (make_fixtures.py): red -> chair, blue -> car, black -> background (none, and
// below min_confidence); its output is half the input (16 x 8), a quarter of a 32 x 16 image,
// so each output pixel is a 4 x 4 block of the image.
TEST(SemanticSegDetector, RunsTheModelAndSplitsItsClassesByDepth) {
  const ClassTable classes = ClassTable::loadDefault();
  const auto det = frontend::loadMaskDetector(kModels + "semantic.yaml", classes);
  EXPECT_EQ(det->name(), "semantic");
  const int w = 32, h = 16;
  frontend::RgbdFrame f;
  f.intrinsics = {w, h, 20.0, 20.0, 16.0, 8.0, 0.001};
  f.color.assign(w * h * 3, 0);
  f.depth.assign(w * h, 2000);
  auto px = [&](int u, int v) { return v * w + u; };
  for (int v = 0; v < 8; ++v)
    for (int u = 0; u < 16; ++u) {
      f.color[3 * px(u, v) + 2] = 255;          // red: chair, ...
      if (u >= 8) f.depth[px(u, v)] = 3000;     // ... its right half 1 m further
    }
  for (int v = 8; v < 16; ++v)
    for (int u = 20; u < 28; ++u) f.color[3 * px(u, v)] = 255;  // blue: car
  f.depth[px(21, 9)] = 0;  // a depth hole in the car
  det->detect(f);
  const int chair = classes.findByName("chair")->id, car = classes.findByName("car")->id;
  ASSERT_EQ(f.instance_class, (std::vector<int>{chair, chair, car}));
  const float p = static_cast<float>(std::exp(2.0) / (std::exp(0.5) + std::exp(2.0) + 1.0));
  for (float c : f.instance_confidence) EXPECT_NEAR(c, p, 1e-5);
  ASSERT_EQ(f.mask.size(), std::size_t(w * h));
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int expected = v < 8 && u < 8 ? 1 : v < 8 && u < 16 ? 2 : v >= 8 && u >= 20 && u < 28 && !(u == 21 && v == 9) ? 3 : 0;
      EXPECT_EQ(f.mask[px(u, v)], expected) << u << ", " << v;
    }
  frontend::RgbdFrame no_depth = f;
  no_depth.depth.clear();
  det->detect(no_depth);
  EXPECT_TRUE(no_depth.instance_class.empty());
  EXPECT_EQ(no_depth.mask, std::vector<std::uint16_t>(w * h, 0));
}

TEST(SemanticSegDetector, BadModelsFailAtLoadNamingFileAndExpectation) {
  const ClassTable classes = ClassTable::loadDefault();
  const std::string shape = errorText([&] { frontend::loadMaskDetector(kModels + "semantic_2.yaml", classes); });
  EXPECT_NE(shape.find("semantic_2.onnx: output [1, 2, 4, 8], expected float [1, 3 classes ("), std::string::npos) << shape;
  EXPECT_NE(shape.find("semantic_2.yaml), 8, 16] or the input size divided by a whole factor"), std::string::npos) << shape;
  const std::string path = testing::TempDir() + "/semantic_missing.yaml";
  std::ofstream(path) << "type: semantic\nmodel: nowhere.onnx\ninput: {width: 16, height: 8}\n"
                         "classes: [{name: x, class: chair}]\n";
  const std::string missing = errorText([&] { frontend::loadMaskDetector(path, classes); });
  EXPECT_NE(missing.find("nowhere.onnx: no such model file (named by " + path + ")"), std::string::npos) << missing;
  frontend::SemanticSegConfig corrupt = frontend::loadSemanticSegConfig(kModels + "semantic.yaml", classes);
  corrupt.model_path = kModels + "corrupt.onnx";
  EXPECT_NE(errorText([&] { frontend::SemanticSegDetector{corrupt}; }).find("corrupt.onnx: not a readable ONNX model"),
            std::string::npos);
}

TEST(SemanticSegDetector, ModelYamlTypeChoosesTheDetector) {
  const ClassTable classes = ClassTable::loadDefault();
  EXPECT_EQ(frontend::loadMaskDetector(kModels + "yolo_seg.yaml", classes)->name(), "yolov8-seg");  // no type key
  const std::string path = testing::TempDir() + "/typed.yaml";
  std::ofstream(path) << "type: yolov8-seg\nmodel: " << kModels << "yolo_seg.onnx\ninput: {width: 32, height: 32}\n"
                      << "classes: [{name: person, class: none}, {name: car, class: car}]\n";
  EXPECT_EQ(frontend::loadMaskDetector(path, classes)->name(), "yolov8-seg");
  std::ofstream(path) << "type: panoptic\nmodel: m.onnx\n";
  const std::string bad = errorText([&] { frontend::loadMaskDetector(path, classes); });
  EXPECT_NE(bad.find("expected yolov8-seg or semantic, not 'panoptic'"), std::string::npos) << bad;
  EXPECT_NE(bad.find("typed.yaml"), std::string::npos) << bad;
}

TEST(SemanticSegDetector, BadConfigsNameFileAndKey) {
  const ClassTable classes = ClassTable::loadDefault();
  const std::string path = testing::TempDir() + "/semantic_bad.yaml";
  auto error = [&](const std::string& extra) {
    std::ofstream(path) << "type: semantic\nmodel: m.onnx\ninput: {width: 16, height: 8}\n"
                        << "classes: [{name: x, class: chair}]\n" << extra;
    return errorText([&] { frontend::loadSemanticSegConfig(path, classes); });
  };
  EXPECT_NE(error("scores: softmax\n").find("expected logits or probabilities"), std::string::npos);
  EXPECT_NE(error("std: [1, 0, 1]\n").find("must be three positive numbers"), std::string::npos);
  EXPECT_NE(error("mean: [1, .nan, 1]\n").find("must be three finite numbers"), std::string::npos);
  EXPECT_NE(error("components: {min_pixels: 0}\n").find("min_pixels"), std::string::npos);
  EXPECT_NE(error("components: {min_pixel: 5}\n").find("unknown key"), std::string::npos);
  EXPECT_NE(error("").find("(nothing thrown)"), std::string::npos);
  const std::string file = error("min_confidence: 2\n");
  EXPECT_NE(file.find("semantic_bad.yaml"), std::string::npos) << file;
  EXPECT_NE(file.find("min_confidence"), std::string::npos) << file;
}
