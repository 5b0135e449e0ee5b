// slide-plot: pictures of a run. `map` draws object maps and trajectories (top or oblique
// view, PNG or SVG); `ate` and `rpe` draw trajectory errors over time.
#include <filesystem>

#include "app/app.h"
#include "eval/trajectory_file.h"
#include "plot_commands.h"

namespace slide {

void addTrajectoryOptions(CLI::App* cmd, TrajectoryArgs& a) {
  cmd->add_option("--format", a.format, "Trajectory format: auto (by columns), tum or kitti")
      ->check(CLI::IsMember({"auto", "tum", "kitti"}))
      ->capture_default_str();
  cmd->add_option("--kitti-times", a.times, "KITTI times file for KITTI poses (else frame index is the time)");
  cmd->add_flag("--kitti-lidar", a.kitti_lidar,
                "KITTI poses are camera poses: convert to the LiDAR frame (x forward, z up) with the 04-10 calibration");
}

std::vector<StampedPose> loadTrajectory(const std::string& path, const TrajectoryArgs& a, const Pose& placement) {
  eval::TrajectoryReadOptions o;
  o.format = eval::parseTrajectoryFormat(a.format);
  o.kitti_times = a.times;
  o.kitti_lidar = a.kitti_lidar;
  o.placement = placement;
  return eval::readTrajectory(path, o);
}

std::string fileStem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

}  // namespace slide

int main(int argc, char** argv) {
  using namespace slide;
  CLI::App app{"slide-plot: pictures of object maps, trajectories and errors (PNG or SVG by --out extension)"};
  app::CommonOptions common;
  app::addCommonOptions(app, common);
  app.require_subcommand(1);
  app.fallthrough();  // --log-level also after the subcommand
  std::vector<std::pair<CLI::App*, PlotCommand>> commands;
  CLI::App* map = app.add_subcommand("map", "Object maps and trajectories, top or oblique view");
  commands.emplace_back(map, addMapCommand(map));
  CLI::App* ate = app.add_subcommand("ate", "Absolute trajectory error per pose over time, one line per EST REF pair");
  commands.emplace_back(ate, addErrorCommand(ate, false));
  CLI::App* rpe = app.add_subcommand("rpe", "Relative pose error over time (at each pair's first pose), one line per pair");
  commands.emplace_back(rpe, addErrorCommand(rpe, true));
  return app::runApp(app, common, argc, argv, [&] {
    for (auto& [sub, cmd] : commands)
      if (sub->parsed()) cmd();
    return 0;
  });
}
