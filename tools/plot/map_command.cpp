// slide-plot map: object maps and trajectories in one picture.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>

#include "io/object_map_text.h"
#include "eval/object_matching.h"
#include "eval/placed_file.h"
#include "plot/map_plot.h"
#include "plot_commands.h"

namespace slide {

PlotCommand addMapCommand(CLI::App* cmd) {
  struct Args {
    std::vector<std::string> maps, trajs, gt_maps, gt_trajs;
    std::string out = "map.png", view = "top", classes, title;
    double azimuth = -60, elevation = 35;
    int width = 1400, height = 1000, default_class = -1;
    bool label_ids = false;
    double score_threshold = 0;
    TrajectoryArgs traj;
  };
  auto a = std::make_shared<Args>();
  const std::string placed = " (FILE or FILE@x,y,z,yaw_deg to place it in the common frame)";
  cmd->add_option("--map", a->maps, "Estimated object map, one per robot in robot order" + placed);
  cmd->add_option("--traj", a->trajs, "Estimated trajectory (TUM or KITTI), one per robot" + placed);
  cmd->add_option("--gt-map", a->gt_maps, "Ground-truth object map" + placed);
  cmd->add_option("--gt-traj", a->gt_trajs, "Ground-truth trajectory" + placed);
  cmd->add_option("--out,-o", a->out, "Output .png or .svg")->capture_default_str();
  cmd->add_option("--view", a->view, "top or oblique")->check(CLI::IsMember({"top", "oblique"}))->capture_default_str();
  cmd->add_option("--azimuth", a->azimuth, "Oblique view: viewer direction around z, degrees from +x")->capture_default_str();
  cmd->add_option("--elevation", a->elevation, "Oblique view: degrees above the horizon")
      ->check(CLI::Range(5.0, 90.0))
      ->capture_default_str();
  cmd->add_option("--classes", a->classes, "Class table (default config/classes.yaml)");
  cmd->add_option("--title", a->title, "Title (default: the file names)");
  cmd->add_option("--width", a->width, "Pixels")->capture_default_str();
  cmd->add_option("--height", a->height, "Pixels")->capture_default_str();
  cmd->add_flag("--label-ids", a->label_ids, "Write object ids next to the objects");
  cmd->add_option("--class", a->default_class, "Class id of objects in CSV maps without a class column (e.g. 80 for x,y pole lists)");
  cmd->add_option("--score", a->score_threshold,
                  "Score the maps against the ground-truth maps with this threshold (m) and draw matches, false "
                  "positives (x) and missed objects (o); precision/recall/F1 in the subtitle");
  addTrajectoryOptions(cmd, a->traj);
  return [a] {
    if (a->maps.empty() && a->trajs.empty() && a->gt_maps.empty() && a->gt_trajs.empty())
      throw std::invalid_argument("map: nothing to draw; give --map, --traj, --gt-map or --gt-traj");
    const ClassTable classes = a->classes.empty() ? ClassTable::loadDefault() : ClassTable::load(a->classes);
    std::vector<plot::PlotMap> maps;
    std::vector<plot::PlotTrajectory> trajs;
    auto addMaps = [&](const std::vector<std::string>& args, bool truth) {
      for (std::size_t i = 0; i < args.size(); ++i) {
        const eval::PlacedFile f = eval::parsePlacedFile(args[i]);
        plot::PlotMap m{fileStem(f.path), {}, static_cast<int>(i), truth};
        for (const Object& o : io::readObjectMapFile(f.path, classes, a->default_class))
          m.objects.push_back(transformObject(f.placement, o));
        spdlog::info("{}: {} objects", f.path, m.objects.size());
        maps.push_back(std::move(m));
      }
    };
    auto addTrajs = [&](const std::vector<std::string>& args, bool truth) {
      for (std::size_t i = 0; i < args.size(); ++i) {
        const eval::PlacedFile f = eval::parsePlacedFile(args[i]);
        plot::PlotTrajectory t{fileStem(f.path), {}, static_cast<int>(i), truth, {}};
        for (const auto& p : loadTrajectory(f.path, a->traj, f.placement)) t.positions.push_back(p.pose.translation());
        spdlog::info("{}: {} poses", f.path, t.positions.size());
        trajs.push_back(std::move(t));
      }
    };
    addMaps(a->maps, false);
    addMaps(a->gt_maps, true);
    addTrajs(a->trajs, false);
    addTrajs(a->gt_trajs, true);
    plot::MapPlotOptions opts;
    opts.view = a->view == "top" ? plot::View::top() : plot::View::oblique(a->azimuth, a->elevation);
    opts.width = a->width;
    opts.height = a->height;
    opts.label_ids = a->label_ids;
    opts.title = a->title;
    if (opts.title.empty()) {
      for (const auto& m : maps) opts.title += (opts.title.empty() ? "" : ", ") + m.name;
      if (opts.title.empty())
        for (const auto& t : trajs) opts.title += (opts.title.empty() ? "" : ", ") + t.name;
    }
    if (a->score_threshold > 0) {
      std::vector<Object> est, gt;
      for (const auto& m : maps) (m.ground_truth ? gt : est).insert((m.ground_truth ? gt : est).end(), m.objects.begin(), m.objects.end());
      if (est.empty() || gt.empty()) throw std::invalid_argument("map --score needs --map and --gt-map");
      eval::ObjectMatchOptions mo;
      mo.threshold = a->score_threshold;
      const eval::ObjectMappingScore sc = eval::scoreObjectMap(est, gt, mo);
      std::vector<bool> est_hit(est.size(), false), gt_hit(gt.size(), false);
      for (const eval::ObjectMatch& m : sc.matches) {
        est_hit[m.est] = gt_hit[m.gt] = true;
        opts.overlay.matches.emplace_back(est[m.est].position(), gt[m.gt].position());
      }
      for (std::size_t i = 0; i < est.size(); ++i)
        if (!est_hit[i]) opts.overlay.false_positives.push_back(est[i].position());
      for (std::size_t i = 0; i < gt.size(); ++i)
        if (!gt_hit[i]) opts.overlay.missed.push_back(gt[i].position());
      char buf[200];
      std::snprintf(buf, sizeof buf, "precision %.3f, recall %.3f, F1 %.3f, position RMSE %.3f m (threshold %g m)",
                    sc.overall.precision, sc.overall.recall, sc.overall.f1, sc.overall.position_rmse, a->score_threshold);
      opts.subtitle = std::string(a->view == "top" ? "top view" : "oblique view") + "; " + buf;
      spdlog::info("{}", buf);
    }
    plot::plotMap(maps, trajs, classes, opts).write(a->out);
    spdlog::info("wrote {}", a->out);
  };
}

}  // namespace slide
