#pragma once
// TUM RGB-D layout of an RGBD robot dataset:
//   rgb/NNNNNN.png        8-bit colour (BGR in memory)
//   depth/NNNNNN.png      16-bit depth, millimetres (depth_scale 0.001), 0 = invalid
//   instances/NNNNNN.png  16-bit per-frame instance ids (0 = none)
//   instances/NNNNNN.txt  one line per instance: "instance_id class_id object_id"
//   rgb.txt, depth.txt    "timestamp path" per frame (TUM lists, '#' comments)
//   associations.txt      "t_rgb rgb/NNNNNN.png t_depth depth/NNNNNN.png" per frame
//   calib.txt             K, size, depth_scale, T_body_camera (io/calib_file.h)
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "geometry/pose.h"

namespace slide::io {

// One line of a TUM RGB-D associations.txt: an RGB image and the depth image taken with it.
struct TumAssociation {
  double t_rgb = 0;
  std::string rgb;  // relative to the dataset folder
  double t_depth = 0;
  std::string depth;
};

struct CameraCalib {
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  double depth_scale = 0.001;  // metres per depth unit
  Pose T_body_camera = Pose::Identity();
};

struct InstanceMask {
  cv::Mat mask;                 // CV_16UC1
  std::vector<int> class_id;    // of instance i + 1
  std::vector<int> object_id;   // ground-truth object of instance i + 1 (0 when unknown)
};

std::vector<TumAssociation> readAssociations(const std::string& path);
void writeAssociations(const std::string& path, const std::vector<TumAssociation>& rows);
// TUM "timestamp path" lists (rgb.txt, depth.txt).
void writeTumImageList(const std::string& path, const std::vector<double>& times, const std::vector<std::string>& files);

CameraCalib readCameraCalib(const std::string& path);
void writeCameraCalib(const std::string& path, const CameraCalib& calib);

// Image readers that check type and size; throw IoError naming the file.
cv::Mat readColorPng(const std::string& path);
cv::Mat readDepthPng(const std::string& path);
void writePng(const std::string& path, const cv::Mat& image);

// The mask PNG and the .txt beside it (same name); every id in the mask must be listed.
InstanceMask readInstanceMask(const std::string& png_path);
void writeInstanceMask(const std::string& png_path, const InstanceMask& mask);

}  // namespace slide::io
