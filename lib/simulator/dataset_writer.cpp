#include "simulator/dataset_writer.h"

#include <atomic>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>
#include <filesystem>
#include <fstream>
#include <memory>

#include "io/calib_file.h"
#include "io/io_error.h"
#include "io/kitti_poses.h"
#include "io/kitti_scan.h"
#include "io/rgbd_files.h"
#include "io/tum_trajectory.h"

namespace fs = std::filesystem;

namespace slide::simulator {

namespace {
std::string frameName(int i, const char* ext) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%06d%s", i, ext);
  return buf;
}

bool hasMovingObjects(const World& w) {
  for (const io::GroundTruthObject& g : w.objects)
    if (g.moving()) return true;
  return false;
}

void writeRobotYaml(const std::string& path, const Scenario& sc, const RobotRun& r, const SensorOptions& s) {
  std::ofstream out(path);
  if (!out) throw io::IoError(path, "cannot write file");
  const Eigen::Vector4d o = xyzYawOf(r.T_world_odom);
  const std::string& sensor = s.sensorOf(r.id);
  out << "robot: " << r.id << "\nworld: " << sc.world.name << "\nseed: " << sc.spec.seed << "\nsensor: " << sensor
      << "\nmodel: " << (sensor == "lidar" ? s.lidar.name : s.camera.name) << "\nframes: " << r.ground_truth.size()
      << "\naerial: " << (r.aerial ? "true" : "false") << "\nfirst_source_frame: " << r.first_source_frame
      << "\n# pose of the robot's odometry frame in the world frame: x y z yaw (metres, radians)\n"
      << "T_world_odom: [" << o[0] << ", " << o[1] << ", " << o[2] << ", " << o[3] << "]\n";
}
}  // namespace

const std::string& SensorOptions::sensorOf(int id) const {
  if (per_robot.empty()) return sensor;
  if (id < 0 || id >= static_cast<int>(per_robot.size()))
    throw std::invalid_argument("no sensor given for robot " + std::to_string(id) + " (" +
                                std::to_string(per_robot.size()) + " sensors listed)");
  return per_robot[id];
}

std::mt19937_64 frameRng(uint64_t seed, int robot, int frame) {
  std::seed_seq seq{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32), static_cast<uint32_t>(robot),
                    static_cast<uint32_t>(frame)};
  return std::mt19937_64(seq);
}

void writeWorldFiles(const Scenario& sc, const std::string& out_dir) {
  fs::create_directories(out_dir);
  io::writeGroundTruthObjects((fs::path(out_dir) / "objects.csv").string(), sc.world.objects);
  const std::string path = (fs::path(out_dir) / "world.yaml").string();
  std::ofstream out(path);
  if (!out) throw io::IoError(path, "cannot write file");
  out << "world: " << sc.world.name << "\nseed: " << sc.spec.seed << "\nrobots: " << sc.robots.size()
      << "\nobjects: " << sc.world.objects.size() << "\noverlap: " << sc.spec.overlap << "\n";
}

GenerationStats writeRobotDataset(const Scenario& sc, const RobotRun& r, const SensorOptions& s, const std::string& dir,
                                  const ProgressFn& progress) {
  const fs::path root(dir);
  fs::create_directories(root);
  const std::string& sensor = s.sensorOf(r.id);
  const bool lidar = sensor == "lidar";
  if (!lidar && sensor != "rgbd") throw std::invalid_argument("unknown sensor '" + sensor + "' (lidar, rgbd)");
  const Trajectory& gt = r.ground_truth;
  std::vector<StampedPose> odom, truth;
  for (std::size_t i = 0; i < gt.size(); ++i) {
    odom.push_back({gt.times[i], r.odometry[i]});
    truth.push_back({gt.times[i], gt.poses[i]});
  }
  io::writeTum((root / "odom.txt").string(), odom);
  io::writeTum((root / "groundtruth.txt").string(), truth);
  writeRobotYaml((root / "robot.yaml").string(), sc, r, s);

  GenerationStats stats;
  std::vector<io::TumAssociation> assoc;
  std::vector<std::string> rgb_files, depth_files;
  if (lidar) {
    fs::create_directories(root / "velodyne");
    fs::create_directories(root / "labels");
    io::writeKittiPoses((root / "poses.txt").string(), gt.poses);
    {
      std::ofstream t(root / "times.txt");
      t.setf(std::ios::fixed);  // microseconds, as odom.txt: frame and odometry times match exactly
      t.precision(6);
      for (double v : gt.times) t << v << '\n';
      if (!t) throw io::IoError((root / "times.txt").string(), "write failed");
    }
    io::writeCalibFile((root / "calib.txt").string(), {{"Tr", io::poseToCalib(Pose::Identity())}});
  } else {
    for (const char* sub : {"rgb", "depth", "instances"}) fs::create_directories(root / sub);
    io::CameraCalib calib;
    calib.width = s.camera.width, calib.height = s.camera.height;
    calib.fx = s.camera.fx, calib.fy = s.camera.fy, calib.cx = s.camera.cx, calib.cy = s.camera.cy;
    calib.T_body_camera.linear() = R_body_optical();
    io::writeCameraCalib((root / "calib.txt").string(), calib);
  }

  const bool moving = hasMovingObjects(sc.world);
  std::unique_ptr<RayCaster> caster;
  const int n = static_cast<int>(gt.size());
  for (int i = 0; i < n; ++i) {
    const double t = gt.times[i];
    if (!caster || moving) caster = std::make_unique<RayCaster>(sc.world, t);
    std::mt19937_64 rng = frameRng(sc.spec.seed, r.id, i);
    if (lidar) {
      const io::LabelledScan scan = simulateLidarScan(*caster, gt.poses[i], s.lidar, rng);
      io::writeVelodyneBin((root / "velodyne" / frameName(i, ".bin")).string(), scan);
      io::writeLabels((root / "labels" / frameName(i, ".label")).string(), scan);
      stats.points += scan.size();
    } else {
      const RgbdImage img = renderRgbd(*caster, gt.poses[i], s.camera, rng);
      const std::string rgb = "rgb/" + frameName(i, ".png"), depth = "depth/" + frameName(i, ".png");
      io::writePng((root / rgb).string(), img.color);
      io::writePng((root / depth).string(), img.depth);
      io::writeInstanceMask((root / "instances" / frameName(i, ".png")).string(),
                        io::InstanceMask{img.instance, img.instance_class, img.instance_object});
      assoc.push_back({gt.times[i], rgb, gt.times[i], depth});
      rgb_files.push_back(rgb);
      depth_files.push_back(depth);
      stats.points += static_cast<std::size_t>(cv::countNonZero(img.depth));
    }
    ++stats.frames;
    if (progress) progress(r.id, i, n);
  }
  if (!lidar) {
    io::writeAssociations((root / "associations.txt").string(), assoc);
    io::writeTumImageList((root / "rgb.txt").string(), gt.times, rgb_files);
    io::writeTumImageList((root / "depth.txt").string(), gt.times, depth_files);
  }
  return stats;
}

GenerationStats writeScenarioDataset(const Scenario& sc, const SensorOptions& s, const std::string& out_dir,
                                     const ProgressFn& progress, unsigned threads) {
  writeWorldFiles(sc, out_dir);
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = std::min<unsigned>(threads, static_cast<unsigned>(sc.robots.size()));
  std::mutex mutex;
  const ProgressFn locked = [&](int r, int i, int n) {
    if (!progress) return;
    std::lock_guard<std::mutex> lock(mutex);
    progress(r, i, n);
  };
  std::vector<GenerationStats> stats(sc.robots.size());
  std::vector<std::exception_ptr> errors(sc.robots.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&]() {
    for (std::size_t k = next++; k < sc.robots.size(); k = next++) {
      const RobotRun& r = sc.robots[k];
      try {
        stats[k] = writeRobotDataset(sc, r, s, (fs::path(out_dir) / ("robot" + std::to_string(r.id))).string(), locked);
      } catch (...) {
        errors[k] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  GenerationStats total;
  for (const GenerationStats& g : stats) {
    total.frames += g.frames;
    total.points += g.points;
  }
  return total;
}

}  // namespace slide::simulator
