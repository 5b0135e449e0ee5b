#pragma once
// Conversions between the front-end's types and its LCM messages (scans, RGBD frames,
// per-frame instances; key-pose bundles: msg/convert.h). Daemons and their tests only.
#include <optional>

#include "frontend/input_issues.h"
#include "frontend/instance.h"
#include "frontend/rgbd_segmenter.h"
#include "io/kitti_scan.h"
#include "slide/frame_instances_t.hpp"
#include "slide/lidar_scan_t.hpp"
#include "slide/rgbd_frame_t.hpp"

namespace slide::msg {

// Labels are dropped (and "label count mismatch" counted) unless num_labels == num_points.
io::LabelledScan fromLcm(const lidar_scan_t& m, frontend::InputIssues& issues);
// Labels when the scan has them; instance ids 0 when it has classes only; intensity 0 where missing.
lidar_scan_t toLcm(const io::LabelledScan& scan, const header_t& header);

// nullopt (and a counted issue) when image byte sizes do not match the intrinsics.
std::optional<frontend::RgbdFrame> fromLcm(const rgbd_frame_t& m, frontend::InputIssues& issues);

frame_instances_t toLcm(const frontend::FrameInstances& f, const header_t& header);
frontend::FrameInstances fromLcm(const frame_instances_t& m);

}  // namespace slide::msg
