#pragma once
// Speed of the RGBD path after a learned detector (its own inference excluded) at 640 x 480,
// on synthetic outputs: a YOLOv8-seg network's (boxes, NMS, masks from prototypes, letterbox
// undone) of the standard export's shape, or a per-pixel semantic network's (classes and
// probabilities per pixel, depth-aware connected components); each then back-projected
// (segmentRgbd).
#include <vector>

#include "frontend/frontend_config.h"
#include "objects/class_table.h"

namespace slide {

// Thread CPU ms per frame, `runs` times: 80 classes, 8400 anchors, `objects` confident
// detections at distinct boxes, random prototypes [1, 32, 160, 160], a 2 m depth plane.
std::vector<double> timeRgbdDecode(const ClassTable& classes, const frontend::FrontendConfig& cfg, int runs,
                                   int objects = 10);

// Thread CPU ms per frame, `runs` times: logits [1, 40, 480 / f, 640 / f] (f = output_factor),
// `objects` chairs 1 m before a wall (both classes confident) at distinct boxes, the rest of
// the classes low; depth 2 m on the chairs, 3 m elsewhere.
std::vector<double> timeSemanticDecode(const ClassTable& classes, const frontend::FrontendConfig& cfg, int runs,
                                       int output_factor = 1, int objects = 10);

}  // namespace slide
