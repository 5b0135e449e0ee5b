// Median depth within instance masks: noise drops, edges and other masks stay put.
#include <gtest/gtest.h>

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
