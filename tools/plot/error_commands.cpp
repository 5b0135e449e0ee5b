// slide-plot ate and rpe: trajectory errors over time.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>
#include <sstream>

#include "eval/ate.h"
#include "eval/error_stats.h"
#include "eval/rpe.h"
#include "eval/time_association.h"
#include "plot/map_plot.h"
#include "plot/palette.h"
#include "plot/series_plot.h"
#include "plot_commands.h"

namespace slide {

PlotCommand addErrorCommand(CLI::App* cmd, bool rpe) {
  struct Args {
    std::vector<std::string> pairs;
    std::string out, align, unit = "frames", title, map_out;
    double max_dt = 0.01, delta = 1.0;
    bool rotation = false;
    TrajectoryArgs traj;
  };
  auto a = std::make_shared<Args>();
  a->out = rpe ? "rpe.png" : "ate.png";
  a->align = rpe ? "none" : "se3";
  cmd->add_option("pairs", a->pairs, "EST REF [EST REF ...] trajectory files")->required();
  cmd->add_option("--out,-o", a->out, "Output .png or .svg")->capture_default_str();
  cmd->add_option("--max-dt", a->max_dt, "Largest time difference of associated poses, seconds")->capture_default_str();
  cmd->add_option("--title", a->title, "Title");
  addTrajectoryOptions(cmd, a->traj);
  if (rpe) {
    cmd->add_option("--delta", a->delta, "Pair spacing, in --unit")->capture_default_str();
    cmd->add_option("--unit", a->unit, "frames or m")->check(CLI::IsMember({"frames", "m"}))->capture_default_str();
    cmd->add_option("--align", a->align, "none, or sim3 to correct the scale first")
        ->check(CLI::IsMember({"none", "sim3"}))
        ->capture_default_str();
    cmd->add_flag("--rotation", a->rotation, "Plot the rotation error (degrees) instead of the translation error");
  } else {
    cmd->add_option("--align", a->align, "none, se3, sim3 or yaw (x, y, z, yaw)")
        ->check(CLI::IsMember({"none", "se3", "sim3", "yaw"}))
        ->capture_default_str();
    cmd->add_option("--map-out", a->map_out,
                    "Also draw a top view (.png/.svg) of the aligned estimates coloured by ATE over the dashed references");
  }
  return [a, rpe] {
    if (a->pairs.size() % 2) throw std::invalid_argument("give trajectory files in EST REF pairs");
    std::vector<plot::Series> series;
    std::vector<plot::PlotTrajectory> paths;
    std::string subtitle;
    for (std::size_t k = 0; k < a->pairs.size(); k += 2) {
      const auto est = loadTrajectory(a->pairs[k], a->traj, Pose::Identity());
      const auto ref = loadTrajectory(a->pairs[k + 1], a->traj, Pose::Identity());
      const eval::AssociatedPoses p = eval::associatePoses(est, ref, a->max_dt, 0.0, 3);
      plot::Series s;
      s.name = fileStem(a->pairs[k]);
      s.colour = plot::robotColour(static_cast<int>(k / 2));
      if (!rpe) {
        const eval::AteResult r = eval::absoluteTrajectoryError(p.est, p.ref, eval::parseAlignment(a->align));
        s.x = p.t;
        s.y = r.errors;
        plot::PlotTrajectory e{s.name + " (aligned)", {}, static_cast<int>(k / 2), false, r.errors};
        plot::PlotTrajectory g{fileStem(a->pairs[k + 1]), {}, static_cast<int>(k / 2), true, {}};
        for (std::size_t i = 0; i < p.t.size(); ++i) {
          e.positions.push_back(r.alignment.scale * (r.alignment.T.linear() * p.est[i].translation()) +
                                r.alignment.T.translation());
          g.positions.push_back(p.ref[i].translation());
        }
        paths.push_back(std::move(e));
        paths.push_back(std::move(g));
      } else {
        eval::RpeOptions o;
        o.delta = a->delta;
        o.unit = a->unit == "m" ? eval::DeltaUnit::Metres : eval::DeltaUnit::Frames;
        if (a->align == "sim3")
          o.scale = eval::absoluteTrajectoryError(p.est, p.ref, eval::TrajectoryAlignment::Sim3).alignment.scale;
        const eval::RpeResult r = eval::relativePoseError(p.est, p.ref, o);
        for (std::size_t i : r.first) s.x.push_back(p.t[i]);
        s.y = a->rotation ? r.rot_errors_deg : r.trans_errors;
      }
      for (double& x : s.x) x -= p.t.front();
      const eval::ErrorStats st = eval::errorStats(s.y);
      char buf[200];
      std::snprintf(buf, sizeof buf, "%s%s: rmse %.3f, max %.3f %s over %zu", subtitle.empty() ? "" : "; ", s.name.c_str(),
                    st.rmse, st.max, rpe && a->rotation ? "deg" : "m", st.count);
      subtitle += buf;
      series.push_back(std::move(s));
    }
    plot::SeriesPlotOptions opts;
    if (!rpe) {
      opts.title = "absolute trajectory error (" + a->align + " alignment)";
      opts.y_label = "ATE [m]";
    } else {
      std::ostringstream t;
      t << "relative pose error, delta " << a->delta << " " << a->unit << (a->align == "sim3" ? " (scale corrected)" : "");
      opts.title = t.str();
      opts.y_label = a->rotation ? "RPE rotation [deg]" : "RPE translation [m]";
    }
    if (!a->title.empty()) opts.title = a->title;
    opts.subtitle = subtitle;
    plot::plotSeries(series, opts).write(a->out);
    spdlog::info("wrote {}", a->out);
    if (!a->map_out.empty()) {
      plot::MapPlotOptions m;
      m.title = opts.title;
      m.subtitle = "estimates coloured by ATE, references dashed (top view)";
      m.values_label = "ATE [m]";
      plot::plotMap({}, paths, ClassTable(), m).write(a->map_out);
      spdlog::info("wrote {}", a->map_out);
    }
  };
}

}  // namespace slide
