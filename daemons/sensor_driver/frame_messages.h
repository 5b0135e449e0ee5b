#pragma once
// Dataset frames as robot-bus messages (slide.rgbd_frame_t, odometry_t; scans go through
// msg/frontend_convert.h).
#include <cstdint>

#include <opencv2/core.hpp>

#include "geometry/pose.h"
#include "io/kitti_scan.h"
#include "io/rgbd_files.h"
#include "slide/header_t.hpp"
#include "slide/odometry_t.hpp"
#include "slide/rgbd_frame_t.hpp"

namespace slide {

// The header of the frame `seq` of `robot` at utime (scans: msg/frontend_convert.h, toLcm).
header_t frameHeader(int64_t utime, int robot, int seq);

// mask may be null (no instances); confidence (one per instance) null means 1.0 each.
// color is 8-bit BGR, depth 16-bit.
rgbd_frame_t toRgbdMessage(const cv::Mat& color, const cv::Mat& depth, const io::InstanceMask* mask,
                           const std::vector<float>* confidence, const io::CameraCalib& calib, int64_t utime, int robot,
                           int seq);

// Body pose in the odometry frame; velocities (body frame) from the previous pose over dt
// seconds (zero when prev is null or dt <= 0).
odometry_t toOdometryMessage(const Pose& pose, const Pose* prev, double dt, int64_t utime, int robot, int seq);

}  // namespace slide
