// slide-plot: pictures of a run. `map` draws object maps and trajectories (top or oblique
// view, PNG or SVG); `ate` draws the absolute trajectory error of each pose over time.
#include <spdlog/spdlog.h>

#include <filesystem>

#include "app/app.h"
#include "eval/ate.h"
#include "eval/object_map_file.h"
#include "eval/placed_file.h"
#include "eval/time_association.h"
#include "eval/trajectory_file.h"
#include "plot/map_plot.h"
#include "plot/palette.h"
#include "plot/series_plot.h"

using namespace slide;

namespace {

struct TrajectoryArgs {
  std::string format = "auto";
  std::string times;
  bool kitti_lidar = false;
};

void addTrajectoryOptions(CLI::App* cmd, TrajectoryArgs& a) {
  cmd->add_option("--format", a.format, "Trajectory format: auto (by columns), tum or kitti")
      ->check(CLI::IsMember({"auto", "tum", "kitti"}))
      ->capture_default_str();
  cmd->add_option("--kitti-times", a.times, "KITTI times file for KITTI poses (else frame index is the time)");
  cmd->add_flag("--kitti-lidar", a.kitti_lidar,
                "KITTI poses are camera poses: convert to the LiDAR frame (x forward, z up) with the 04-10 calibration");
}

std::vector<StampedPose> loadTrajectory(const std::string& path, const TrajectoryArgs& a, const Pose& placement) {
  TrajectoryReadOptions o;
  o.format = parseTrajectoryFormat(a.format);
  o.kitti_times = a.times;
  o.kitti_lidar = a.kitti_lidar;
  o.placement = placement;
  return readTrajectory(path, o);
}

std::string stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

std::vector<Eigen::Vector3d> positions(const std::vector<StampedPose>& t) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : t) out.push_back(p.pose.translation());
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"slide-plot: pictures of object maps, trajectories and errors (PNG or SVG by --out extension)"};
  CommonOptions common;
  addCommonOptions(app, common);
  app.require_subcommand(1);
  app.fallthrough();  // --log-level also after the subcommand

  // map
  CLI::App* map_cmd = app.add_subcommand("map", "Object maps and trajectories, top or oblique view");
  std::vector<std::string> maps, trajs, gt_maps, gt_trajs;
  std::string out = "map.png", view = "top", classes_path, title;
  double azimuth = -60, elevation = 35;
  int width = 1400, height = 1000;
  bool label_ids = false;
  int default_class = -1;
  TrajectoryArgs traj_args;
  const char* placed = " (FILE or FILE@x,y,z,yaw_deg to place it in the common frame)";
  map_cmd->add_option("--map", maps, std::string("Estimated object map, one per robot in robot order") + placed);
  map_cmd->add_option("--traj", trajs, std::string("Estimated trajectory (TUM or KITTI), one per robot") + placed);
  map_cmd->add_option("--gt-map", gt_maps, std::string("Ground-truth object map") + placed);
  map_cmd->add_option("--gt-traj", gt_trajs, std::string("Ground-truth trajectory") + placed);
  map_cmd->add_option("--out,-o", out, "Output .png or .svg")->capture_default_str();
  map_cmd->add_option("--view", view, "top or oblique")->check(CLI::IsMember({"top", "oblique"}))->capture_default_str();
  map_cmd->add_option("--azimuth", azimuth, "Oblique view: viewer direction around z, degrees from +x")->capture_default_str();
  map_cmd->add_option("--elevation", elevation, "Oblique view: degrees above the horizon")
      ->check(CLI::Range(5.0, 90.0))
      ->capture_default_str();
  map_cmd->add_option("--classes", classes_path, "Class table (default config/classes.yaml)");
  map_cmd->add_option("--title", title, "Title (default: the map file names)");
  map_cmd->add_option("--width", width, "Pixels")->capture_default_str();
  map_cmd->add_option("--height", height, "Pixels")->capture_default_str();
  map_cmd->add_flag("--label-ids", label_ids, "Write object ids next to the objects");
  map_cmd->add_option("--class", default_class, "Class id of objects in CSV maps without a class column (e.g. 80 for x,y pole lists)");
  addTrajectoryOptions(map_cmd, traj_args);

  // ate
  CLI::App* ate_cmd = app.add_subcommand("ate", "Absolute trajectory error per pose over time, one line per pair");
  std::vector<std::string> pairs;
  std::string ate_out = "ate.png", align = "se3";
  double max_dt = 0.01;
  TrajectoryArgs ate_traj;
  ate_cmd->add_option("pairs", pairs, "EST REF [EST REF ...] trajectory files")->required();
  ate_cmd->add_option("--out,-o", ate_out, "Output .png or .svg")->capture_default_str();
  ate_cmd->add_option("--align", align, "none, se3, sim3 or yaw (x, y, z, yaw)")
      ->check(CLI::IsMember({"none", "se3", "sim3", "yaw"}))
      ->capture_default_str();
  ate_cmd->add_option("--max-dt", max_dt, "Largest time difference of associated poses, seconds")->capture_default_str();
  ate_cmd->add_option("--title", title, "Title");
  addTrajectoryOptions(ate_cmd, ate_traj);

  return runApp(app, common, argc, argv, [&]() -> int {
    const ClassTable classes = classes_path.empty() ? ClassTable::loadDefault() : ClassTable::load(classes_path);
    if (map_cmd->parsed()) {
      if (maps.empty() && trajs.empty() && gt_maps.empty() && gt_trajs.empty())
        throw std::invalid_argument("map: nothing to draw; give --map, --traj, --gt-map or --gt-traj");
      std::vector<PlotMap> plot_maps;
      std::vector<PlotTrajectory> plot_trajs;
      auto addMaps = [&](const std::vector<std::string>& args, bool truth) {
        for (std::size_t i = 0; i < args.size(); ++i) {
          const PlacedFile f = parsePlacedFile(args[i]);
          PlotMap m{stem(f.path), {}, static_cast<int>(i), truth};
          for (const Object& o : readObjectMapFile(f.path, classes, default_class)) m.objects.push_back(transformObject(f.placement, o));
          spdlog::info("{}: {} objects", f.path, m.objects.size());
          plot_maps.push_back(std::move(m));
        }
      };
      auto addTrajs = [&](const std::vector<std::string>& args, bool truth) {
        for (std::size_t i = 0; i < args.size(); ++i) {
          const PlacedFile f = parsePlacedFile(args[i]);
          const auto t = loadTrajectory(f.path, traj_args, f.placement);
          spdlog::info("{}: {} poses", f.path, t.size());
          plot_trajs.push_back({stem(f.path), positions(t), static_cast<int>(i), truth});
        }
      };
      addMaps(maps, false);
      addMaps(gt_maps, true);
      addTrajs(trajs, false);
      addTrajs(gt_trajs, true);
      MapPlotOptions opts;
      opts.view = view == "top" ? View::top() : View::oblique(azimuth, elevation);
      opts.width = width;
      opts.height = height;
      opts.label_ids = label_ids;
      if (title.empty()) {
        for (const auto& m : plot_maps) title += (title.empty() ? "" : ", ") + m.name;
        if (title.empty())
          for (const auto& t : plot_trajs) title += (title.empty() ? "" : ", ") + t.name;
      }
      opts.title = title;
      plotMap(plot_maps, plot_trajs, classes, opts).write(out);
      spdlog::info("wrote {}", out);
      return 0;
    }
    // ate
    if (pairs.size() % 2) throw std::invalid_argument("ate: give trajectory files in EST REF pairs");
    const Alignment mode = align == "none" ? Alignment::None
                           : align == "se3" ? Alignment::Se3
                           : align == "sim3" ? Alignment::Sim3
                                             : Alignment::Yaw4Dof;
    std::vector<Series> series;
    std::string subtitle;
    for (std::size_t k = 0; k < pairs.size(); k += 2) {
      const auto est = loadTrajectory(pairs[k], ate_traj, Pose::Identity());
      const auto ref = loadTrajectory(pairs[k + 1], ate_traj, Pose::Identity());
      const AssociatedPoses a = associatePoses(est, ref, max_dt, 0.0, 3);
      const AteResult r = absoluteTrajectoryError(a.est, a.ref, mode);
      Series s;
      s.name = stem(pairs[k]);
      s.colour = robotColour(static_cast<int>(k / 2));
      for (std::size_t i = 0; i < a.t.size(); ++i) {
        s.x.push_back(a.t[i] - a.t.front());
        s.y.push_back(r.errors[i]);
      }
      series.push_back(s);
      char buf[160];
      std::snprintf(buf, sizeof buf, "%s%s: rmse %.3f m, max %.3f m, %zu poses", subtitle.empty() ? "" : "; ",
                    s.name.c_str(), r.rmse, r.max, a.t.size());
      subtitle += buf;
    }
    SeriesPlotOptions opts;
    opts.title = title.empty() ? "absolute trajectory error (" + align + " alignment)" : title;
    opts.subtitle = subtitle;
    opts.y_label = "ATE [m]";
    plotSeries(series, opts).write(ate_out);
    spdlog::info("wrote {}", ate_out);
    return 0;
  });
}
