#include "frontend/depth_filter.h"

#include <algorithm>

namespace slide::frontend {

std::vector<std::uint16_t> medianDepthWithinMasks(const std::vector<std::uint16_t>& depth,
                                                  const std::vector<std::uint16_t>& mask, int width, int height,
                                                  int radius) {
  std::vector<std::uint16_t> out = depth;
  if (radius <= 0) return out;
  std::vector<std::uint16_t> window;
  window.reserve(static_cast<std::size_t>((2 * radius + 1) * (2 * radius + 1)));
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * width + u;
      const std::uint16_t id = mask[i];
      if (id == 0 || depth[i] == 0) continue;
      window.clear();
      for (int y = std::max(0, v - radius); y <= std::min(height - 1, v + radius); ++y) {
        const std::size_t row = static_cast<std::size_t>(y) * width;
        for (int x = std::max(0, u - radius); x <= std::min(width - 1, u + radius); ++x) {
          const std::size_t j = row + x;
          if (mask[j] == id && depth[j] != 0) window.push_back(depth[j]);
        }
      }
      auto mid = window.begin() + static_cast<std::ptrdiff_t>(window.size() / 2);
      std::nth_element(window.begin(), mid, window.end());
      out[i] = *mid;
    }
  return out;
}

}  // namespace slide::frontend
