#include "eval/trajectory_file.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io/io_error.h"
#include "io/kitti_poses.h"

namespace slide::eval {

TrajectoryFormat parseTrajectoryFormat(const std::string& s) {
  if (s == "auto") return TrajectoryFormat::Auto;
  if (s == "tum") return TrajectoryFormat::Tum;
  if (s == "kitti") return TrajectoryFormat::Kitti;
  throw std::invalid_argument("trajectory format must be auto, tum or kitti, got '" + s + "'");
}

namespace {
TrajectoryFormat detect(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw io::IoError(path, "cannot open file");
  std::string line;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream s(line);
    std::string tok;
    int n = 0;
    while (s >> tok) ++n;
    if (n == 8) return TrajectoryFormat::Tum;
    if (n == 12) return TrajectoryFormat::Kitti;
    throw io::IoError(path, "first line has " + std::to_string(n) +
                            " values; expected 8 (TUM: t tx ty tz qx qy qz qw) or 12 (KITTI 3x4 pose)");
  }
  throw io::IoError(path, "no poses in file");
}
}  // namespace

std::vector<StampedPose> readTrajectory(const std::string& path, TrajectoryFormat format,
                                        const std::string& kitti_times_path) {
  if (format == TrajectoryFormat::Auto) format = detect(path);
  if (format == TrajectoryFormat::Tum) return io::readTum(path);
  const std::vector<Pose> poses = io::readKittiPoses(path);
  std::vector<double> times;
  if (!kitti_times_path.empty()) {
    times = io::readKittiTimes(kitti_times_path);
    if (times.size() != poses.size())
      throw io::IoError(kitti_times_path, "has " + std::to_string(times.size()) + " times for " +
                                          std::to_string(poses.size()) + " poses in " + path);
  }
  std::vector<StampedPose> out;
  for (std::size_t i = 0; i < poses.size(); ++i) out.push_back({times.empty() ? double(i) : times[i], poses[i]});
  return out;
}

std::vector<StampedPose> readTrajectory(const std::string& path, const TrajectoryReadOptions& opts) {
  std::vector<StampedPose> t = readTrajectory(path, opts.format, opts.kitti_times);
  if (opts.kitti_lidar) {
    std::vector<Pose> cam;
    for (const auto& p : t) cam.push_back(p.pose);
    const auto lidar = io::kittiLidarPoses(cam, io::kittiVeloToCamTr0410());
    for (std::size_t i = 0; i < t.size(); ++i) t[i].pose = lidar[i];
  }
  for (auto& p : t) p.pose = opts.placement * p.pose;
  return t;
}

}  // namespace slide::eval
