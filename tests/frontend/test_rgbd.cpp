// RGBD instance backprojection: depth band around the mask's median, confidence gate, bad input.
#include <gtest/gtest.h>

#include "frontend/rgbd_segmenter.h"

using namespace slide;

namespace {
// 64x48 frame: instance 1 is a 20x20 square at 2 m whose mask also covers 40 background pixels
// at 6 m; instance 2 is a low-confidence square.
frontend::RgbdFrame makeFrame() {
  frontend::RgbdFrame f;
  f.intrinsics = {64, 48, 50, 50, 32, 24, 0.001};
  f.depth.assign(64 * 48, 6000);
  f.mask.assign(64 * 48, 0);
  for (int v = 10; v < 30; ++v)
    for (int u = 10; u < 30; ++u) {
      f.depth[v * 64 + u] = 2000 + (u % 3) * 10;
      f.mask[v * 64 + u] = 1;
    }
  for (int u = 10; u < 30; ++u) f.mask[30 * 64 + u] = f.mask[31 * 64 + u] = 1;  // bleeding onto the background
  for (int v = 5; v < 15; ++v)
    for (int u = 40; u < 50; ++u) f.mask[v * 64 + u] = 2;
  f.instance_class = {1, 2};
  f.instance_confidence = {0.9f, 0.2f};
  return f;
}
}  // namespace

TEST(RgbdSegmenter, BackprojectsInsideTheDepthBand) {
  const ClassTable classes = ClassTable::loadDefault();
  frontend::InputIssues issues;
  const auto inst = frontend::segmentRgbd(makeFrame(), classes, {}, issues);
  ASSERT_EQ(inst.size(), 1u);  // the low-confidence instance is gated
  EXPECT_EQ(inst[0].class_id, 1);
  EXPECT_EQ(inst[0].points.size(), 400u);  // background pixels of the mask are dropped
  for (const auto& p : inst[0].points) {
    EXPECT_NEAR(p.x(), 2.01, 0.02);  // body x = optical depth
    EXPECT_LT(std::abs(p.y()), 1.0);
  }
  // Optical (u right, v down) maps to body (y left, z up): pixel column 10 is left of centre.
  float max_y = -1e9f;
  for (const auto& p : inst[0].points) max_y = std::max(max_y, p.y());
  EXPECT_NEAR(max_y, (32 - 10) * 2.0 / 50, 0.05);
  EXPECT_EQ(issues.total(), 0);
}

TEST(RgbdSegmenter, BadInputIsCountedNotFatal) {
  const ClassTable classes = ClassTable::loadDefault();
  frontend::RgbdFrame f = makeFrame();
  for (int u = 10; u < 20; ++u) f.depth[12 * 64 + u] = 0;
  f.instance_class[1] = 999;
  frontend::InputIssues issues;
  EXPECT_EQ(frontend::segmentRgbd(f, classes, {}, issues).size(), 1u);
  EXPECT_EQ(issues.get("zero depth in mask"), 10);
  EXPECT_EQ(issues.get("unknown class"), 1);

  frontend::RgbdFrame small = makeFrame();
  small.depth.resize(100);
  EXPECT_TRUE(frontend::segmentRgbd(small, classes, {}, issues).empty());
  EXPECT_EQ(issues.get("image size does not match intrinsics"), 1);
  frontend::RgbdFrame no_k = makeFrame();
  no_k.intrinsics.fx = 0;
  EXPECT_TRUE(frontend::segmentRgbd(no_k, classes, {}, issues).empty());
  EXPECT_EQ(issues.get("invalid intrinsics"), 1);
}

// erode_px 2: the square's edge pixels (depth 2 m, on the object) stay, judged by their own
// depth; the mask's two rows spilled onto the background at 6 m go. With restore_edges off
// (the old behaviour) the square loses its 2-pixel rim and with it a fifth of its width.
TEST(RgbdSegmenter, EdgePixelsOnTheObjectStaySpilledOnesGo) {
  const ClassTable classes = ClassTable::loadDefault();
  frontend::RgbdSegmenterParams p;
  p.erode_px = 2;
  frontend::InputIssues issues;
  const auto inst = frontend::segmentRgbd(makeFrame(), classes, p, issues);
  ASSERT_EQ(inst.size(), 1u);
  EXPECT_EQ(inst[0].points.size(), 400u);
  float lo = 1e9f, hi = -1e9f;
  for (const auto& q : inst[0].points) {
    EXPECT_NEAR(q.x(), 2.01, 0.02);
    lo = std::min(lo, q.y()), hi = std::max(hi, q.y());
  }
  EXPECT_NEAR(hi - lo, 19 * 2.0 / 50, 0.01);  // columns 10-29 at 2.00-2.02 m, fx 50
  p.restore_edges = false;
  const auto eroded = frontend::segmentRgbd(makeFrame(), classes, p, issues);
  ASSERT_EQ(eroded.size(), 1u);
  lo = 1e9f, hi = -1e9f;
  for (const auto& q : eroded[0].points) lo = std::min(lo, q.y()), hi = std::max(hi, q.y());
  EXPECT_NEAR(hi - lo, 15 * 2.0 / 50, 0.01);
}
