// Median depth within instance masks: noise drops, edges and other masks stay put.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "frontend/depth_filter.h"

using namespace slide;

TEST(DepthFilter, ReducesNoiseWithoutLeakingAcrossMasks) {
  const int w = 40, h = 30;
  std::vector<std::uint16_t> depth(w * h, 0), mask(w * h, 0);
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0, 100);  // 0.1 m in millimetres
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int i = v * w + u;
      mask[i] = u < 20 ? 1 : 2;                // two instances side by side
      depth[i] = static_cast<std::uint16_t>((u < 20 ? 5000 : 9000) + n(rng));
    }
  depth[5 * w + 5] = 0;  // missing depth stays missing
  const auto out = frontend::medianDepthWithinMasks(depth, mask, w, h, 2);
  double e_in = 0, e_out = 0;
  int count = 0;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int i = v * w + u;
      if (depth[i] == 0) {
        EXPECT_EQ(out[i], 0);
        continue;
      }
      const double truth = u < 20 ? 5000 : 9000;
      e_in += std::pow(depth[i] - truth, 2), e_out += std::pow(out[i] - truth, 2), ++count;
      EXPECT_LT(std::abs(out[i] - truth), 400);  // no pixel takes the other instance's depth
    }
  EXPECT_LT(std::sqrt(e_out / count), 0.5 * std::sqrt(e_in / count));
  EXPECT_EQ(frontend::medianDepthWithinMasks(depth, mask, w, h, 0), depth);
}

// Every pixel takes the upper median of the valid pixels of its own mask in its window, as a
// plain gather and sort gives it: random blobs of three ids, 5 % missing depth and few distinct
// depths (ties everywhere), windows of radius 1-3; pixels outside masks or without depth keep
// their value.
TEST(DepthFilter, EachPixelTakesTheMedianOfItsMasksValidPixels) {
  const int w = 97, h = 61;
  std::vector<std::uint16_t> depth(w * h), mask(w * h, 0);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> d(400, 440);
  std::uniform_real_distribution<double> u01(0, 1);
  for (int k = 0; k < 9; ++k) {  // rectangles of ids 1-3, later ones over earlier ones
    const int u0 = static_cast<int>(u01(rng) * w), v0 = static_cast<int>(u01(rng) * h);
    const int du = 5 + static_cast<int>(u01(rng) * 40), dv = 5 + static_cast<int>(u01(rng) * 30);
    for (int v = v0; v < std::min(h, v0 + dv); ++v)
      for (int u = u0; u < std::min(w, u0 + du); ++u) mask[v * w + u] = static_cast<std::uint16_t>(1 + k % 3);
  }
  for (auto& z : depth) z = u01(rng) < 0.05 ? 0 : static_cast<std::uint16_t>(d(rng));
  for (int radius : {1, 2, 3}) {
    const auto out = frontend::medianDepthWithinMasks(depth, mask, w, h, radius);
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) {
        const int i = v * w + u;
        if (mask[i] == 0 || depth[i] == 0) {
          ASSERT_EQ(out[i], depth[i]);
          continue;
        }
        std::vector<std::uint16_t> win;
        for (int y = std::max(0, v - radius); y <= std::min(h - 1, v + radius); ++y)
          for (int x = std::max(0, u - radius); x <= std::min(w - 1, u + radius); ++x)
            if (mask[y * w + x] == mask[i] && depth[y * w + x] != 0) win.push_back(depth[y * w + x]);
        std::sort(win.begin(), win.end());
        ASSERT_EQ(out[i], win[win.size() / 2]) << "pixel " << u << ", " << v << ", radius " << radius;
      }
  }
}
