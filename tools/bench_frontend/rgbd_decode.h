#pragma once
// Speed of the RGBD path after a YOLOv8-seg network (its own inference excluded): decoding
// (boxes, NMS, masks from prototypes, letterbox undone) and back-projection of the masks
// (segmentRgbd) at 640 x 480, on synthetic outputs of the standard export's shape.
#include <vector>

#include "frontend/frontend_config.h"
#include "objects/class_table.h"

namespace slide {

// Thread CPU ms per frame, `runs` times: 80 classes, 8400 anchors, `objects` confident
// detections at distinct boxes, random prototypes [1, 32, 160, 160], a 2 m depth plane.
std::vector<double> timeRgbdDecode(const ClassTable& classes, const frontend::FrontendConfig& cfg, int runs,
                                   int objects = 10);

}  // namespace slide
