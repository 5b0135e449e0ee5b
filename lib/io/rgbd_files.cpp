#include "io/rgbd_files.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "io/calib_file.h"
#include "io/io_error.h"

namespace slide::io {

namespace {
bool skip(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  return first == std::string::npos || line[first] == '#';
}

std::string txtBeside(const std::string& png) { return std::filesystem::path(png).replace_extension(".txt").string(); }
}  // namespace

std::vector<TumAssociation> readAssociations(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path, "cannot open file");
  std::vector<TumAssociation> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (skip(line)) continue;
    std::istringstream s(line);
    TumAssociation a;
    if (!(s >> a.t_rgb >> a.rgb >> a.t_depth >> a.depth))
      throw IoError(path, "line " + std::to_string(n) + ": expected 't_rgb rgb_file t_depth depth_file'");
    out.push_back(a);
  }
  return out;
}

void writeAssociations(const std::string& path, const std::vector<TumAssociation>& rows) {
  std::ofstream out(path);
  if (!out) throw IoError(path, "cannot write file");
  out << std::fixed << std::setprecision(6);
  for (const TumAssociation& a : rows) out << a.t_rgb << ' ' << a.rgb << ' ' << a.t_depth << ' ' << a.depth << '\n';
  if (!out) throw IoError(path, "write failed");
}

void writeTumImageList(const std::string& path, const std::vector<double>& times, const std::vector<std::string>& files) {
  std::ofstream out(path);
  if (!out) throw IoError(path, "cannot write file");
  out << "# timestamp filename\n" << std::fixed << std::setprecision(6);
  for (std::size_t i = 0; i < times.size() && i < files.size(); ++i) out << times[i] << ' ' << files[i] << '\n';
  if (!out) throw IoError(path, "write failed");
}

CameraCalib readCameraCalib(const std::string& path) {
  const CalibEntries e = readCalibFile(path);
  CameraCalib c;
  const std::vector<double> K = calibValues(e, path, "K", 9);
  c.fx = K[0], c.cx = K[2], c.fy = K[4], c.cy = K[5];
  const std::vector<double> size = calibValues(e, path, "size", 2);
  c.width = static_cast<int>(size[0]), c.height = static_cast<int>(size[1]);
  if (c.width <= 0 || c.height <= 0 || c.fx <= 0 || c.fy <= 0) throw IoError(path, "non-positive image size or focal length");
  c.depth_scale = calibValues(e, path, "depth_scale", 1)[0];
  c.T_body_camera = calibPose(e, path, "T_body_camera");
  return c;
}

void writeCameraCalib(const std::string& path, const CameraCalib& c) {
  writeCalibFile(path, {{"K", {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1}},
                        {"size", {static_cast<double>(c.width), static_cast<double>(c.height)}},
                        {"depth_scale", {c.depth_scale}},
                        {"T_body_camera", poseToCalib(c.T_body_camera)}});
}

cv::Mat readColorPng(const std::string& path) {
  if (!std::filesystem::exists(path)) throw IoError(path, "missing file");
  cv::Mat m = cv::imread(path, cv::IMREAD_COLOR);
  if (m.empty()) throw IoError(path, "not a readable image (truncated or corrupt)");
  return m;
}

cv::Mat readDepthPng(const std::string& path) {
  if (!std::filesystem::exists(path)) throw IoError(path, "missing file");
  cv::Mat m = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (m.empty()) throw IoError(path, "not a readable image (truncated or corrupt)");
  if (m.type() != CV_16UC1) throw IoError(path, "depth must be a 16-bit single-channel PNG");
  return m;
}

void writePng(const std::string& path, const cv::Mat& image) {
  if (!cv::imwrite(path, image)) throw IoError(path, "cannot write image");
}

InstanceMask readInstanceMask(const std::string& png_path) {
  InstanceMask m;
  m.mask = readDepthPng(png_path);
  const std::string txt = txtBeside(png_path);
  std::ifstream in(txt);
  if (!in) throw IoError(txt, "cannot open file");
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (skip(line)) continue;
    std::istringstream s(line);
    int id, cls, obj;
    if (!(s >> id >> cls >> obj)) throw IoError(txt, "line " + std::to_string(n) + ": expected 'instance_id class_id object_id'");
    if (id != static_cast<int>(m.class_id.size()) + 1)
      throw IoError(txt, "line " + std::to_string(n) + ": instance ids must count up from 1");
    m.class_id.push_back(cls);
    m.object_id.push_back(obj);
  }
  double max_id = 0;
  cv::minMaxLoc(m.mask, nullptr, &max_id);
  if (max_id > static_cast<double>(m.class_id.size()))
    throw IoError(png_path, "mask holds instance " + std::to_string(static_cast<int>(max_id)) + " but " + txt + " lists " +
                                std::to_string(m.class_id.size()));
  return m;
}

void writeInstanceMask(const std::string& png_path, const InstanceMask& m) {
  writePng(png_path, m.mask);
  const std::string txt = txtBeside(png_path);
  std::ofstream out(txt);
  if (!out) throw IoError(txt, "cannot write file");
  out << "# instance_id class_id object_id\n";
  for (std::size_t i = 0; i < m.class_id.size(); ++i)
    out << i + 1 << ' ' << m.class_id[i] << ' ' << (i < m.object_id.size() ? m.object_id[i] : 0) << '\n';
  if (!out) throw IoError(txt, "write failed");
}

}  // namespace slide::io
