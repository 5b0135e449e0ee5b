// slide-plot: pictures of a run. `map` draws object maps and trajectories (top or oblique
// view, PNG or SVG); `ate` and `rpe` draw trajectory errors over time.
#include <spdlog/spdlog.h>

#include <filesystem>
#include <sstream>

#include "app/app.h"
#include "eval/ate.h"
#include "eval/error_stats.h"
#include "eval/rpe.h"
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

  // ate and rpe: errors over time, one line per EST REF pair.
  struct ErrorArgs {
    std::vector<std::string> pairs;
    std::string out, align, unit = "frames";
    double max_dt = 0.01, delta = 1.0;
    bool rotation = false;
    TrajectoryArgs traj;
  };
  ErrorArgs ate_args{{}, "ate.png", "se3"}, rpe_args{{}, "rpe.png", "none"};
  auto addErrorOptions = [&](CLI::App* cmd, ErrorArgs& a) {
    cmd->add_option("pairs", a.pairs, "EST REF [EST REF ...] trajectory files")->required();
    cmd->add_option("--out,-o", a.out, "Output .png or .svg")->capture_default_str();
    cmd->add_option("--max-dt", a.max_dt, "Largest time difference of associated poses, seconds")->capture_default_str();
    cmd->add_option("--title", title, "Title");
    addTrajectoryOptions(cmd, a.traj);
  };
  CLI::App* ate_cmd = app.add_subcommand("ate", "Absolute trajectory error per pose over time, one line per pair");
  addErrorOptions(ate_cmd, ate_args);
  ate_cmd->add_option("--align", ate_args.align, "none, se3, sim3 or yaw (x, y, z, yaw)")
      ->check(CLI::IsMember({"none", "se3", "sim3", "yaw"}))
      ->capture_default_str();
  CLI::App* rpe_cmd = app.add_subcommand("rpe", "Relative pose error over time (at each pair's first pose), one line per pair");
  addErrorOptions(rpe_cmd, rpe_args);
  rpe_cmd->add_option("--delta", rpe_args.delta, "Pair spacing, in --unit")->capture_default_str();
  rpe_cmd->add_option("--unit", rpe_args.unit, "frames or m")->check(CLI::IsMember({"frames", "m"}))->capture_default_str();
  rpe_cmd->add_option("--align", rpe_args.align, "none, or sim3 to correct the scale first")
      ->check(CLI::IsMember({"none", "sim3"}))
      ->capture_default_str();
  rpe_cmd->add_flag("--rotation", rpe_args.rotation, "Plot the rotation error (degrees) instead of the translation error");

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
    const bool ate = ate_cmd->parsed();
    const ErrorArgs& e = ate ? ate_args : rpe_args;
    if (e.pairs.size() % 2) throw std::invalid_argument("give trajectory files in EST REF pairs");
    std::vector<Series> series;
    std::string subtitle;
    for (std::size_t k = 0; k < e.pairs.size(); k += 2) {
      const auto est = loadTrajectory(e.pairs[k], e.traj, Pose::Identity());
      const auto ref = loadTrajectory(e.pairs[k + 1], e.traj, Pose::Identity());
      const AssociatedPoses a = associatePoses(est, ref, e.max_dt, 0.0, 3);
      Series s;
      s.name = stem(e.pairs[k]);
      s.colour = robotColour(static_cast<int>(k / 2));
      std::vector<double> errors;
      if (ate) {
        const AteResult r = absoluteTrajectoryError(a.est, a.ref, parseAlignment(e.align));
        s.x = a.t;
        s.y = r.errors;
      } else {
        RpeOptions o;
        o.delta = e.delta;
        o.unit = e.unit == "m" ? DeltaUnit::Metres : DeltaUnit::Frames;
        if (e.align == "sim3") o.scale = absoluteTrajectoryError(a.est, a.ref, Alignment::Sim3).alignment.scale;
        const RpeResult r = relativePoseError(a.est, a.ref, o);
        for (std::size_t i = 0; i < r.first.size(); ++i) s.x.push_back(a.t[r.first[i]]);
        s.y = e.rotation ? r.rot_errors_deg : r.trans_errors;
      }
      for (double& x : s.x) x -= a.t.front();
      const ErrorStats st = errorStats(s.y);
      char buf[200];
      std::snprintf(buf, sizeof buf, "%s%s: rmse %.3f, max %.3f %s over %zu", subtitle.empty() ? "" : "; ", s.name.c_str(),
                    st.rmse, st.max, ate || !e.rotation ? "m" : "deg", st.count);
      subtitle += buf;
      series.push_back(std::move(s));
    }
    SeriesPlotOptions opts;
    if (ate) {
      opts.title = "absolute trajectory error (" + e.align + " alignment)";
      opts.y_label = "ATE [m]";
    } else {
      std::ostringstream t;
      t << "relative pose error, delta " << e.delta << " " << e.unit << (e.align == "sim3" ? " (scale corrected)" : "");
      opts.title = t.str();
      opts.y_label = e.rotation ? "RPE rotation [deg]" : "RPE translation [m]";
    }
    if (!title.empty()) opts.title = title;
    opts.subtitle = subtitle;
    plotSeries(series, opts).write(e.out);
    spdlog::info("wrote {}", e.out);
    return 0;
  });
}
