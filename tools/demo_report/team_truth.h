#pragma once
// Ground truth of a simulated team run: each robot's odometry frame in the world, its true
// trajectory, and the world's objects (simulator output folder: robotN/, objects.csv).
#include <string>
#include <vector>

#include "io/tum_trajectory.h"
#include "objects/object.h"

namespace slide {

struct RobotTruth {
  int robot = 0;
  Pose T_world_odom = Pose::Identity();  // the robot's odometry frame in the world
  std::vector<StampedPose> ground_truth;  // world frame
  std::vector<StampedPose> odometry;      // own odometry frame
  double path_length_m = 0;
  std::string platform;  // e.g. "ground LiDAR", "aerial RGBD" (robot.yaml of the simulator)
};

struct TeamTruth {
  std::vector<RobotTruth> robots;
  std::vector<Object> objects;  // static objects, world frame
  const RobotTruth& robot(int id) const;
  // True transform mapping robot b's odometry frame into robot a's.
  Pose T_a_b(int a, int b) const;
};

// Reads DATA/robot<id>/ for each id and DATA/objects.csv; throws naming the missing file.
TeamTruth readTeamTruth(const std::string& data_dir, const std::vector<int>& robots);

}  // namespace slide
