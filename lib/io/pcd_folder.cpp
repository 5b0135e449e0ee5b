#include "io/pcd_folder.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/io_error.h"
#include "io/kitti_poses.h"
#include "io/pcd_file.h"
#include "io/tum_trajectory.h"

namespace fs = std::filesystem;

namespace slide::io {

namespace {
std::vector<std::string> pcdFiles(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".pcd") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

class PcdReader : public FrameReader {
 public:
  explicit PcdReader(std::vector<std::string> files) : files_(std::move(files)) {}
  LabelledScan scan(std::size_t id) const override { return readPcdFile(files_.at(id)); }
  RgbdImages rgbd(std::size_t) const override { throw std::logic_error("a PCD folder has no RGBD frames"); }

 private:
  std::vector<std::string> files_;
};

double timeFromName(const std::string& path) {
  const std::string stem = fs::path(path).stem().string();
  std::size_t used = 0;
  double t = 0;
  try {
    t = std::stod(stem, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != stem.size() || !std::isfinite(t))
    throw IoError(path, "no times.txt, and the file name is not a time (seconds or nanoseconds)");
  return t > 1e15 ? t * 1e-9 : t;
}
}  // namespace

bool isPcdFolder(const std::string& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".pcd") return true;
  return false;
}

RobotDataset openPcdFolder(const std::string& dir, const DatasetOptions& options) {
  RobotDataset d;
  d.path = dir;
  d.sensor = RobotDataset::Sensor::Lidar;
  std::vector<std::string> files = pcdFiles(dir);
  std::vector<double> times;
  const fs::path times_txt = fs::path(dir) / "times.txt";
  if (fs::exists(times_txt)) {
    times = readKittiTimes(times_txt.string());
    if (times.size() != files.size())
      throw IoError(times_txt.string(), "times: " + std::to_string(times.size()) + " entries for " +
                                            std::to_string(files.size()) + " .pcd files");
  } else {
    for (const std::string& f : files) times.push_back(timeFromName(f));
  }
  const fs::path odom = fs::path(dir) / "odom.txt";
  if (!fs::exists(odom)) throw IoError(odom.string(), "missing: a PCD folder needs its odometry (TUM trajectory, any rate)");
  const std::vector<StampedPose> traj = readTum(odom.string());
  d.reader = std::make_shared<PcdReader>(std::move(files));
  keepFramesWithOdometry(d, times, [&](double t, Pose& T) { return poseAtTime(traj, t, options.max_odometry_gap_s, T); });
  return d;
}

}  // namespace slide::io
