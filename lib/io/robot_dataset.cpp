#include "io/robot_dataset.h"

#include <algorithm>
#include <filesystem>

#include "io/calib_file.h"
#include "io/io_error.h"
#include "io/kitti_poses.h"

namespace fs = std::filesystem;

namespace slide {

namespace {
void checkCount(const std::string& path, const char* what, std::size_t got, std::size_t frames) {
  if (got != frames)
    throw IoError(path, std::string(what) + ": " + std::to_string(got) + " entries for " + std::to_string(frames) + " frames");
}

void openLidar(RobotDataset& d) {
  const fs::path dir(d.dir);
  for (const auto& e : fs::directory_iterator(dir / "velodyne"))
    if (e.path().extension() == ".bin") d.scans.push_back(e.path().string());
  std::sort(d.scans.begin(), d.scans.end());
  if (d.scans.empty()) throw IoError((dir / "velodyne").string(), "no .bin scans");
  const fs::path times = dir / "times.txt";
  if (fs::exists(times)) {
    d.times = readKittiTimes(times.string());
    checkCount(times.string(), "times", d.times.size(), d.scans.size());
  } else {
    for (std::size_t i = 0; i < d.scans.size(); ++i) d.times.push_back(0.1 * static_cast<double>(i));
  }
  const fs::path odom = dir / "odom.txt", poses = dir / "poses.txt", calib = dir / "calib.txt";
  if (!fs::exists(odom) && fs::exists(poses)) {
    Pose Tr = Pose::Identity();
    if (fs::exists(calib)) Tr = calibPose(readCalibFile(calib.string()), calib.string(), "Tr");
    const std::vector<Pose> p = kittiLidarPoses(readKittiPoses(poses.string()), Tr);
    checkCount(poses.string(), "poses", p.size(), d.scans.size());
    for (std::size_t i = 0; i < p.size(); ++i) d.odometry.push_back({d.times[i], p[i]});
  }
}

void openRgbd(RobotDataset& d) {
  const fs::path dir(d.dir);
  d.frames = readAssociations((dir / "associations.txt").string());
  if (d.frames.empty()) throw IoError((dir / "associations.txt").string(), "no frames");
  for (const Association& a : d.frames) {
    for (const std::string& f : {a.rgb, a.depth})
      if (!fs::exists(dir / f)) throw IoError((dir / f).string(), "missing file listed in associations.txt");
    d.times.push_back(a.t_rgb);
  }
  d.camera = readCameraCalib((dir / "calib.txt").string());
}
}  // namespace

RobotDataset openRobotDataset(const std::string& dir) {
  if (!fs::is_directory(dir)) throw IoError(dir, "missing dataset folder");
  RobotDataset d;
  d.dir = dir;
  if (fs::is_directory(fs::path(dir) / "velodyne")) {
    d.sensor = RobotDataset::Sensor::Lidar;
    openLidar(d);
  } else if (fs::exists(fs::path(dir) / "associations.txt")) {
    d.sensor = RobotDataset::Sensor::Rgbd;
    openRgbd(d);
  } else {
    throw IoError(dir, "neither a KITTI layout (velodyne/) nor a TUM RGB-D layout (associations.txt)");
  }
  const fs::path odom = fs::path(dir) / "odom.txt", gt = fs::path(dir) / "groundtruth.txt";
  if (fs::exists(odom)) {
    d.odometry = readTum(odom.string());
    checkCount(odom.string(), "odometry poses", d.odometry.size(), d.size());
  }
  if (fs::exists(gt)) {
    d.ground_truth = readTum(gt.string());
    checkCount(gt.string(), "ground-truth poses", d.ground_truth.size(), d.size());
  }
  return d;
}

}  // namespace slide
