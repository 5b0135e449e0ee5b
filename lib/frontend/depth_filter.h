#pragma once
// Depth denoising inside instance masks. Stereo depth noise grows with the square of the
// depth (a D455 is about 0.3 m off per pixel at 9 m), enough to smear a car's faces into
// blobs whose footprint rectangle turns by 90 degrees. Each pixel of an instance takes the
// median depth of the valid pixels of the same instance within a square window: planar faces
// keep their shape, the noise drops with the window size, and no depth leaks across mask edges.
#include <cstdint>
#include <vector>

namespace slide::frontend {

// Filtered copy of `depth` (width*height raw units, 0 = missing) for the pixels whose `mask`
// id is non-zero; other pixels are copied. radius 0 returns the input unchanged.
std::vector<std::uint16_t> medianDepthWithinMasks(const std::vector<std::uint16_t>& depth,
                                                  const std::vector<std::uint16_t>& mask, int width, int height,
                                                  int radius);

}  // namespace slide::frontend
