#include "io/lidar_folder_writer.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "io/calib_file.h"
#include "io/io_error.h"
#include "io/kitti_scan.h"
#include "io/tum_trajectory.h"

namespace fs = std::filesystem;

namespace slide::io {

LidarFolderReport writeLidarFolder(const RobotDataset& d, const std::string& dir) {
  if (d.sensor != RobotDataset::Sensor::Lidar)
    throw IoError(dir, "only LiDAR recordings can be written as a dataset folder (" + d.path + " is RGBD)");
  if (fs::exists(dir) && (!fs::is_directory(dir) || !fs::is_empty(dir)))
    throw IoError(dir, "output folder exists and is not empty");
  const fs::path root(dir);
  fs::create_directories(root / "velodyne");
  LidarFolderReport report;
  std::vector<StampedPose> odom;
  for (std::size_t i = 0; i < d.size(); ++i) {
    LabelledScan scan;
    try {
      scan = d.scan(i);
    } catch (const IoError& e) {
      report.unreadable.push_back(e.what());
      continue;
    }
    char name[32];
    std::snprintf(name, sizeof name, "%06zu.bin", report.written++);
    writeVelodyneBin((root / "velodyne" / name).string(), scan);
    odom.push_back(d.odometry[i]);
  }
  if (odom.empty()) throw IoError(d.path, "no frame could be read; nothing written to " + dir);
  std::ofstream t(root / "times.txt");
  t.setf(std::ios::fixed);  // microseconds, as odom.txt: frame and odometry times match exactly
  t.precision(6);
  for (const StampedPose& p : odom) t << p.t << '\n';
  if (!t) throw IoError((root / "times.txt").string(), "write failed");
  writeTum((root / "odom.txt").string(), odom);
  writeCalibFile((root / "calib.txt").string(), {{"Tr", poseToCalib(Pose::Identity())}});
  return report;
}

}  // namespace slide::io
