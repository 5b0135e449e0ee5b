#pragma once
// Decoding of a per-pixel semantic segmentation network's scores into depth-separated
// instances; no network here (semantic_seg_detector.h runs one).
//   scores [1, K, h, w] (float): one score per model class per output pixel, logits or
//   probabilities. The network saw the whole image resized (stretched, no letterbox) to its
//   input, and its output covers the same area, so image pixel (u, v) reads output pixel
//   (floor((u + 0.5) * w / width), floor((v + 0.5) * h / height)): nearest neighbour, for any
//   h, w (the input size or a fraction of it).
// Per image pixel: the best-scoring class and its probability (softmax of logits); below
// min_confidence the pixel is unlabelled. Instances are the 4-connected components of
// labelled pixels with depth: two neighbours join when they have the same class and their
// depths differ by at most max(depth_step_m, depth_step_fraction * the nearer depth).
// Pixels without depth (0) join no instance: they could not be back-projected, and a depth
// hole on an object's edge may as well be its background. Components of fewer than
// min_pixels pixels are dropped. An instance's confidence is the mean probability of its
// class over its pixels.
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "frontend/rgbd_segmenter.h"

namespace slide::frontend {

struct SemanticSegParams {
  bool logits = true;            // false: the scores are probabilities already
  double min_confidence = 0.5;   // probability a pixel's class needs (0: every pixel labelled)
  double depth_step_m = 0.10;    // neighbours' depth difference always allowed (metres) ...
  double depth_step_fraction = 0.05;  // ... or this fraction of the nearer depth, if larger
  int min_pixels = 50;           // smaller components are dropped
};

// Per image pixel (row-major, width * height): its model class (-1: unlabelled) and that
// class's probability (0 where unlabelled).
struct PixelClasses {
  int width = 0, height = 0;
  std::vector<int> model_class;
  std::vector<float> probability;
};

// Throws std::invalid_argument naming the expected shape when `scores` is not float
// [1, classes, h, w], and for non-positive image sizes.
PixelClasses classifyPixels(const cv::Mat& scores, int classes, int image_width, int image_height,
                            const SemanticSegParams& params);

struct SemanticInstance {
  int model_class = 0;
  float confidence = 0;     // mean probability over the pixels
  std::vector<int> pixels;  // row-major image indices, in no particular order
};

// The depth-aware components (in the raster order of their first pixel). `depth` holds
// width * height raw units (0: missing) scaled to metres by depth_scale; a depth image of
// another size gives no instances.
std::vector<SemanticInstance> depthComponents(const PixelClasses& pixels, const std::vector<std::uint16_t>& depth,
                                              double depth_scale, const SemanticSegParams& params);

// Appends the instances whose model class maps to one of ours (class_of_model[k] >= 0) to the
// frame, as paintInstances (yolo_seg_decoder.h) does: instance_class, instance_confidence and
// their pixels in frame.mask (id = index + 1). Pixels outside the frame are skipped; at most
// 65535 instances.
void paintSemanticInstances(const std::vector<SemanticInstance>& instances, const std::vector<int>& class_of_model,
                            RgbdFrame& frame);

}  // namespace slide::frontend
