#include "io/robot_dataset.h"

#include <algorithm>
#include <filesystem>

#include "io/calib_file.h"
#include "io/io_error.h"
#include "io/kitti_poses.h"
#include "io/pcd_folder.h"
#include "io/ros_bag.h"
#include "io/tum_trajectory.h"

namespace fs = std::filesystem;

namespace slide::io {

namespace {
void checkCount(const std::string& path, const char* what, std::size_t got, std::size_t frames) {
  if (got != frames)
    throw IoError(path, std::string(what) + ": " + std::to_string(got) + " entries for " + std::to_string(frames) + " frames");
}

class KittiFolderReader : public FrameReader {
 public:
  explicit KittiFolderReader(std::vector<std::string> scans) : scans_(std::move(scans)) {}
  LabelledScan scan(std::size_t id) const override { return readLabelledScan(scans_.at(id)); }
  RgbdImages rgbd(std::size_t) const override { throw std::logic_error("a KITTI folder has no RGBD frames"); }

 private:
  std::vector<std::string> scans_;
};

class TumFolderReader : public FrameReader {
 public:
  TumFolderReader(fs::path dir, std::vector<TumAssociation> frames) : dir_(std::move(dir)), frames_(std::move(frames)) {}
  LabelledScan scan(std::size_t) const override { throw std::logic_error("a TUM RGB-D folder has no LiDAR scans"); }
  RgbdImages rgbd(std::size_t id) const override {
    const TumAssociation& a = frames_.at(id);
    RgbdImages f;
    f.color = readColorPng((dir_ / a.rgb).string());
    f.depth = readDepthPng((dir_ / a.depth).string());
    const fs::path mask = dir_ / "instances" / fs::path(a.rgb).filename();
    if (fs::exists(mask)) f.mask = readInstanceMask(mask.string());
    return f;
  }

 private:
  fs::path dir_;
  std::vector<TumAssociation> frames_;
};

std::vector<double> openKitti(RobotDataset& d) {
  const fs::path dir(d.path);
  std::vector<std::string> scans;
  for (const auto& e : fs::directory_iterator(dir / "velodyne"))
    if (e.path().extension() == ".bin") scans.push_back(e.path().string());
  std::sort(scans.begin(), scans.end());
  if (scans.empty()) throw IoError((dir / "velodyne").string(), "no .bin scans");
  const fs::path times = dir / "times.txt";
  if (!fs::exists(times)) throw IoError(times.string(), "missing (one time in seconds per scan)");
  std::vector<double> t = readKittiTimes(times.string());
  checkCount(times.string(), "times", t.size(), scans.size());
  d.reader = std::make_shared<KittiFolderReader>(std::move(scans));
  return t;
}

std::vector<double> openTum(RobotDataset& d) {
  const fs::path dir(d.path);
  std::vector<TumAssociation> frames = readAssociations((dir / "associations.txt").string());
  if (frames.empty()) throw IoError((dir / "associations.txt").string(), "no frames");
  std::vector<double> t;
  for (const TumAssociation& a : frames) {
    for (const std::string& f : {a.rgb, a.depth})
      if (!fs::exists(dir / f)) throw IoError((dir / f).string(), "missing file listed in associations.txt");
    t.push_back(a.t_rgb);
  }
  d.camera = readCameraCalib((dir / "calib.txt").string());
  d.reader = std::make_shared<TumFolderReader>(dir, std::move(frames));
  return t;
}

// odom.txt of a folder, required, sorted by time.
std::vector<StampedPose> readOdometryFile(const fs::path& dir) {
  const fs::path odom = dir / "odom.txt";
  if (!fs::exists(odom))
    throw IoError(odom.string(), "missing: a folder needs its odometry (TUM trajectory 't x y z qx qy qz qw', any rate)");
  std::vector<StampedPose> traj = readTum(odom.string());
  if (traj.empty()) throw IoError(odom.string(), "no poses");
  return traj;
}
}  // namespace

void keepFramesWithOdometry(RobotDataset& d, const std::vector<double>& times, const PoseAtTimeFn& pose_at) {
  d.times.clear(), d.frame_ids.clear(), d.odometry.clear();
  d.dropped = {};
  for (std::size_t k = 0; k < times.size(); ++k) {
    Pose T = Pose::Identity();
    const PoseMiss miss = pose_at(times[k], T);
    if (miss == PoseMiss::OutsideSpan) ++d.dropped.outside_span;
    if (miss == PoseMiss::Gap) ++d.dropped.gap;
    if (miss != PoseMiss::None) continue;
    d.times.push_back(times[k]);
    d.frame_ids.push_back(k);
    d.odometry.push_back({times[k], T});
  }
  if (d.times.empty())
    throw IoError(d.path, "none of the " + std::to_string(times.size()) + " frames has an odometry pose (" +
                              std::to_string(d.dropped.outside_span) + " outside the odometry's time span, " +
                              std::to_string(d.dropped.gap) + " in gaps)");
}

RobotDataset openRobotDataset(const std::string& path, const DatasetOptions& options) {
  if (fs::is_regular_file(path) && fs::path(path).extension() == ".bag") return openBagDataset(path, options);
  if (!fs::is_directory(path)) throw IoError(path, "missing dataset folder (or .bag file)");
  if (!fs::is_directory(fs::path(path) / "velodyne") && isPcdFolder(path)) return openPcdFolder(path, options);
  RobotDataset d;
  d.path = path;
  std::vector<double> times;
  if (fs::is_directory(fs::path(path) / "velodyne")) {
    d.sensor = RobotDataset::Sensor::Lidar;
    times = openKitti(d);
  } else if (fs::exists(fs::path(path) / "associations.txt")) {
    d.sensor = RobotDataset::Sensor::Rgbd;
    times = openTum(d);
  } else {
    throw IoError(path, "neither a KITTI layout (velodyne/) nor a TUM RGB-D layout (associations.txt) nor a PCD folder (*.pcd)");
  }
  const std::vector<StampedPose> odom = readOdometryFile(path);
  keepFramesWithOdometry(d, times, [&](double t, Pose& T) { return poseAtTime(odom, t, options.max_odometry_gap_s, T); });
  const fs::path gt = fs::path(path) / "groundtruth.txt";
  if (fs::exists(gt)) d.ground_truth = readTum(gt.string());
  return d;
}

}  // namespace slide::io
