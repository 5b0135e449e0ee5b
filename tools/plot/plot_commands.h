#pragma once
// The subcommands of slide-plot: each registers its options and returns what runs when chosen.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "io/tum_trajectory.h"

namespace slide {

using PlotCommand = std::function<void()>;

PlotCommand addMapCommand(CLI::App* cmd);
// ATE per pose over time (rpe = false) or RPE per pair over time (rpe = true).
PlotCommand addErrorCommand(CLI::App* cmd, bool rpe);

// Trajectory reading options shared by the subcommands.
struct TrajectoryArgs {
  std::string format = "auto";
  std::string times;
  bool kitti_lidar = false;
};
void addTrajectoryOptions(CLI::App* cmd, TrajectoryArgs& a);
std::vector<StampedPose> loadTrajectory(const std::string& path, const TrajectoryArgs& a, const Pose& placement);
std::string fileStem(const std::string& path);

}  // namespace slide
