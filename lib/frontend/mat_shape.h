#pragma once
// The text of an n-dimensional matrix's shape, "[1, 38, 8400]", for the errors that name what
// a network gave against what was expected.
#include <string>

#include <opencv2/core.hpp>

namespace slide::frontend {

inline std::string shapeText(const cv::Mat& m) {
  std::string t = "[";
  for (int d = 0; d < m.dims; ++d) t += (d ? ", " : "") + std::to_string(m.size[d]);
  return t + "]";
}

}  // namespace slide::frontend
