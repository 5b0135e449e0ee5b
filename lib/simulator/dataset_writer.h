#pragma once
// Writes a scenario to disk, one folder per robot:
//   OUT/objects.csv                 ground-truth objects (io/ground_truth_objects.h)
//   OUT/world.yaml                  world name, seed, robot count
//   OUT/robotN/robot.yaml           robot id, sensor, frames, T_world_odom (x y z yaw)
//   OUT/robotN/odom.txt             odometry, TUM trajectory in the robot's own frame
//   OUT/robotN/groundtruth.txt      ground-truth body poses, TUM trajectory, world frame
//   LiDAR (KITTI layout): velodyne/NNNNNN.bin, labels/NNNNNN.label, poses.txt (ground-truth
//     LiDAR poses in the world frame, 3x4), times.txt, calib.txt (Tr = identity)
//   RGBD (TUM layout, io/rgbd_files.h): rgb/, depth/, instances/, rgb.txt, depth.txt,
//     associations.txt, calib.txt
// The LiDAR sits at the body origin; the camera too, looking along body x.
#include <functional>
#include <string>
#include <vector>

#include "simulator/lidar.h"
#include "simulator/rgbd_camera.h"
#include "simulator/scenario.h"

namespace slide::simulator {

struct SensorOptions {
  std::string sensor = "lidar";  // lidar | rgbd
  std::vector<std::string> per_robot;  // mixed teams: robot r carries per_robot[r] (else `sensor`)
  LidarModel lidar = lidarModel("os1-64");
  CameraModel camera = cameraModel("d455");
  // The sensor robot `id` carries.
  const std::string& sensorOf(int id) const;
};

struct GenerationStats {
  std::size_t frames = 0;
  std::size_t points = 0;  // LiDAR points or valid depth pixels
};

// Called after each frame with (robot, frame index, frames of that robot); with several
// threads it is called from all of them (one call at a time).
using ProgressFn = std::function<void(int, int, int)>;

// The random generator of one sensor frame: depends only on the seed, robot and frame.
std::mt19937_64 frameRng(uint64_t seed, int robot, int frame);

// Writes objects.csv and world.yaml into out_dir (created if needed).
void writeWorldFiles(const Scenario& scenario, const std::string& out_dir);
// Writes one robot's folder (trajectories and every sensor frame) with the sensor s.sensorOf(robot.id).
GenerationStats writeRobotDataset(const Scenario& scenario, const RobotRun& robot, const SensorOptions& sensor,
                                  const std::string& robot_dir, const ProgressFn& progress = {});
// Both of the above for every robot (OUT/robotN), robots in parallel on up to `threads`
// threads (0: one per core). The output does not depend on the thread count.
GenerationStats writeScenarioDataset(const Scenario& scenario, const SensorOptions& sensor, const std::string& out_dir,
                                     const ProgressFn& progress = {}, unsigned threads = 0);

}  // namespace slide::simulator
