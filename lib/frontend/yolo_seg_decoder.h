#pragma once
// Decoding of a YOLOv8-seg network's outputs (the ultralytics ONNX export) into instance
// masks; no network here (yolo_seg_detector.h runs one).
//   output0 [1, 4 + classes + 32, anchors]: per anchor the box centre x, y, width, height in
//           network-input pixels, one score per class, 32 mask coefficients;
//   output1 [1, 32, mh, mw]: prototype masks at 1/4 of the input resolution (any mh, mw).
// The input is the colour image letterboxed: scaled by s = min(in_w / w, in_h / h), centred,
// padded. Decoding: anchors whose best class scores at least score_threshold, greedy NMS per
// class (IoU above nms_iou suppresses the lower score), at most max_detections; each mask is
// sigmoid(coefficients . prototypes) sampled bilinearly at each image pixel's centre mapped
// through the letterbox into the prototypes (one resize from prototype to image, the border
// replicated), thresholded (> mask_threshold), within the box only.
#include <vector>

#include <opencv2/core.hpp>

#include "frontend/rgbd_segmenter.h"

namespace slide::frontend {

// image -> network input: x_in = x * scale + pad_x, y_in = y * scale + pad_y.
struct Letterbox {
  double scale = 1.0;
  int pad_x = 0, pad_y = 0;
  int width = 0, height = 0;  // the scaled image inside the input (pixels)
};
// Throws std::invalid_argument for non-positive sizes.
Letterbox letterboxOf(int image_width, int image_height, int input_width, int input_height);
// The BGR image letterboxed into an input_width x input_height BGR image (padding grey 114).
cv::Mat letterboxImage(const cv::Mat& bgr, const Letterbox& lb, int input_width, int input_height);

struct YoloSegParams {
  int input_width = 640, input_height = 640;
  double score_threshold = 0.25;
  double nms_iou = 0.45;
  double mask_threshold = 0.5;
  int max_detections = 100;
};

struct YoloInstance {
  int model_class = 0;  // index into the model's classes
  float score = 0;
  cv::Rect2d box;       // image pixels (x, y, width, height), clipped to the image
  cv::Mat mask;         // CV_8U image-size, 255 inside
};

// Throws std::invalid_argument naming the expected shapes when output0 is not
// [1, 4 + classes + 32, anchors] or output1 not [1, 32, mh, mw] (float).
std::vector<YoloInstance> decodeYoloSeg(const cv::Mat& output0, const cv::Mat& output1, int classes, const Letterbox& lb,
                                        int image_width, int image_height, const YoloSegParams& params);

// Appends the instances whose model class maps to one of ours (class_of_model[k] >= 0) to
// the frame: instance_class, instance_confidence, and their pixels in frame.mask (id = index
// + 1) where no earlier (higher-scoring) instance holds them. Masks not of the frame's size
// are skipped.
void paintInstances(const std::vector<YoloInstance>& instances, const std::vector<int>& class_of_model, RgbdFrame& frame);

// Intersection over union of two boxes (0 for empty ones).
double boxIou(const cv::Rect2d& a, const cv::Rect2d& b);

}  // namespace slide::frontend
