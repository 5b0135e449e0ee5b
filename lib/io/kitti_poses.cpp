#include "io/kitti_poses.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "io/io_error.h"

namespace slide::io {

namespace {
std::ifstream openOrThrow(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path, "cannot open file");
  return in;
}

bool blank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }
}  // namespace

std::vector<Pose> readKittiPoses(const std::string& path) {
  std::ifstream in = openOrThrow(path);
  std::vector<Pose> poses;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (blank(line)) continue;
    std::istringstream s(line);
    Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        if (!(s >> M(r, c)) || !std::isfinite(M(r, c)))
          throw IoError(path, "line " + std::to_string(n) + ": expected 12 finite numbers (3x4 pose)");
    std::string extra;
    if (s >> extra) throw IoError(path, "line " + std::to_string(n) + ": more than 12 values");
    Pose T = Pose::Identity();
    T.matrix() = M;
    poses.push_back(T);
  }
  return poses;
}

void writeKittiPoses(const std::string& path, const std::vector<Pose>& poses) {
  std::ofstream out(path);
  if (!out) throw IoError(path, "cannot write file");
  out << std::setprecision(9) << std::scientific;
  for (const Pose& T : poses) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) out << T.matrix()(r, c) << (r == 2 && c == 3 ? '\n' : ' ');
  }
}

std::vector<double> readKittiTimes(const std::string& path) {
  std::ifstream in = openOrThrow(path);
  std::vector<double> times;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (blank(line)) continue;
    std::istringstream s(line);
    double t;
    if (!(s >> t) || !std::isfinite(t)) throw IoError(path, "line " + std::to_string(n) + ": expected a time in seconds");
    times.push_back(t);
  }
  return times;
}

Pose kittiVeloToCamTr0410() {
  Pose Tr = Pose::Identity();
  Tr.matrix().topRows<3>() << -1.857739385241e-03, -9.999659513510e-01, -7.215806671127e-03, -4.784029760483e-03,
      -6.481465826011e-03, 7.228698582701e-03, -9.999528809118e-01, -7.337429464231e-02, 9.999773098287e-01,
      -1.805361832319e-03, -6.496203536139e-03, -3.339968064433e-01;
  return Tr;
}

std::vector<Pose> kittiLidarPoses(const std::vector<Pose>& cam_poses, const Pose& Tr) {
  std::vector<Pose> out;
  out.reserve(cam_poses.size());
  Pose Tr_inv = Pose::Identity();
  Tr_inv.matrix() = Tr.matrix().inverse();  // Tr is not exactly orthonormal
  for (const Pose& P : cam_poses) out.push_back(Tr_inv * P * Tr);
  return out;
}

}  // namespace slide::io
