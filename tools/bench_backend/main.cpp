// slide-bench-backend: per-key-pose update time, batch baseline and accuracy of the back-end
// on the indoor, urban, forest and KITTI 05/07 scenarios (BENCHMARKS.md names).
#include <spdlog/spdlog.h>

#include <sys/resource.h>

#include <algorithm>
#include <iostream>
#include <numeric>

#include "app/app.h"
#include "backend/backend_config.h"
#include "bench/report.h"
#include "bench/stats.h"
#include "io/kitti_poses.h"
#include "config/config.h"
#include "map_size.h"
#include "place/loop_closer_config.h"
#include "realistic_run.h"
#include "graph_scenario/realism.h"
#include "scenario_run.h"

using namespace slide;

namespace {
double peakRssMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

double processCpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Targets {
  std::optional<double> median, p99;
  std::optional<double> paper_ate;
  std::string anchor;  // iSAM2 / paper timing figures quoted by the issue
};

void report(bench::BenchReport& rep, const std::string& name, const ScenarioRunResult& r, const Targets& t) {
  const std::string n = std::to_string(r.update_ms.size()) + " updates, one run";
  rep.add(name + ".update_ms.median", bench::median(r.update_ms), "ms", true, t.median).note = n + "; " + t.anchor;
  rep.add(name + ".update_ms.p99", bench::quantile(r.update_ms, 0.99), "ms", true, t.p99).note =
      n + ", loop closures and merges included; " + t.anchor;
  rep.add(name + ".update_ms.max", bench::quantile(r.update_ms, 1.0), "ms");
  rep.add(name + ".update_cpu_ms.median", bench::median(r.update_cpu_ms), "ms").note =
      "thread CPU time of the same updates";
  rep.add(name + ".update_cpu_ms.p99", bench::quantile(r.update_cpu_ms, 0.99), "ms");
  const double total_cpu = std::accumulate(r.update_cpu_ms.begin(), r.update_cpu_ms.end(), 0.0);
  rep.add(name + ".update_cpu_total_s", total_cpu / 1000.0, "s");
  const double total = std::accumulate(r.update_ms.begin(), r.update_ms.end(), 0.0);
  auto& tot = rep.add(name + ".update_total_s", total / 1000.0, "s", true,
                      name == "forest" ? std::optional<double>(2.5) : std::nullopt);
  tot.note = std::to_string(r.full_solves) + " full solves inside, " + std::to_string(r.loop_closures) +
             " intra-robot loop closures";
  rep.add(name + ".final_solve_ms", r.final_solve_ms, "ms").note = "full solve after the last update";
  rep.add(name + ".batch_ms", r.batch_ms, "ms").note = "same graph solved from scratch (baseline)";
  rep.add(name + ".batch_cpu_ms", r.batch_cpu_ms, "ms");
  rep.add(name + ".final_solve_cpu_ms", r.final_solve_cpu_ms, "ms");
  rep.add(name + ".cost_gap", std::abs(r.incremental_cost - r.batch_cost) / std::max(1e-9, r.batch_cost), "").note =
      "relative final-cost difference, incremental vs batch";
  rep.add(name + ".ate_m", r.ate_m, "m", true, r.odom_ate_m / 3.0, t.paper_ate).note = "target: a third of odometry's";
  rep.add(name + ".batch_ate_m", r.batch_ate_m, "m");
  rep.add(name + ".odom_ate_m", r.odom_ate_m, "m");
  rep.add(name + ".landmarks", r.landmarks, "", false).note =
      std::to_string(r.true_landmarks_seen) + " true landmarks seen";
  rep.add(name + ".landmark_rmse_m", r.landmark_rmse_m, "m");
  rep.add(name + ".wrong_associations", r.wrong_association_fraction, "").note =
      "fraction of detections joined to another object's landmark";
  rep.add(name + ".keyposes", r.keyposes, "", false).note =
      std::to_string(r.objects_per_keypose).substr(0, 4) + " objects per key pose";
}
// Object map sizes as shared (team::encodeMap) per robot and in total, against raw scans.
void reportMapSizes(bench::BenchReport& rep, const std::string& name, const std::vector<RobotMapSize>& sizes,
                    double points) {
  double kb = 0, raw_mb = 0;
  int objects = 0;
  long frames = 0;
  for (const RobotMapSize& r : sizes) {
    const std::string p = name + ".robot" + std::to_string(r.robot) + ".";
    rep.add(p + "map_kb", r.map_bytes / 1000.0, "KB").note =
        std::to_string(r.objects) + " objects, its own map encoded for sharing (team::encodeMap)";
    rep.add(p + "map_objects", r.objects, "", false);
    rep.add(p + "raw_scans_mb", r.raw_bytes / 1e6, "MB").note = std::to_string(r.frames) + " LiDAR frames";
    kb += r.map_bytes / 1000.0, raw_mb += r.raw_bytes / 1e6, objects += r.objects, frames += r.frames;
  }
  const std::string n = std::to_string(sizes.size());
  rep.add(name + ".map_kb", kb, "KB").note = "sum of the " + n + " robots' own object maps, encoded for sharing";
  rep.add(name + ".map_objects", objects, "", false).note = "sum over the " + n + " robots";
  rep.add(name + ".raw_scans_mb", raw_mb, "MB").note =
      std::to_string(frames) + " frames x " + std::to_string(static_cast<long>(points)) +
      " points (mean of the real SemanticKITTI HDL-64E scans) x 16 B";
  rep.add(name + ".map_compression", kb > 0 ? raw_mb * 1000.0 / kb : 0.0, "x", false).note = "raw scans / object maps";
}
// A realistic case: detections with misses, false objects, class confusion and noise the
// estimator does not know; closures and transforms from place recognition on own maps.
void reportRealistic(bench::BenchReport& rep, const std::string& name, const RealisticRunResult& r,
                     const graph_scenario::ScenarioRealism& realism, std::optional<double> paper_ate) {
  const std::string p = name + "_realistic.";
  const std::string cond = "REALISTIC: " + realism.describe() +
                           "; closures and transforms from place recognition on the robots' own maps";
  rep.add(p + "update_ms.median", bench::median(r.update_ms), "ms").note = cond;
  rep.add(p + "update_ms.p99", bench::quantile(r.update_ms, 0.99), "ms");
  rep.add(p + "update_ms.max", bench::quantile(r.update_ms, 1.0), "ms");
  rep.add(p + "ate_m", r.ate_m, "m", true, r.odom_ate_m / 3.0, paper_ate).note =
      "host and merged peers after a final solve; target: a third of odometry's" +
      std::string(paper_ate ? "; 'paper': the published figure, quoted" : "");
  rep.add(p + "odom_ate_m", r.odom_ate_m, "m").note = "the same robots' odometry, peers placed by the transforms given";
  rep.add(p + "host_ate_m", r.host_ate_m, "m", true, r.host_odom_ate_m).note =
      "the host's own trajectory; target: never above its odometry's";
  rep.add(p + "host_odom_ate_m", r.host_odom_ate_m, "m");
  rep.add(p + "peers_merged", r.peers_merged, "", true, static_cast<double>(r.peers)).note =
      "of " + std::to_string(r.peers) + " peers";
  rep.add(p + "intra_closures", r.intra_closures, "", false).note = "the host loop closer's, given to its optimizer";
  rep.add(p + "wrong_intra_closures", r.wrong_intra, "", true, 0.0).note =
      "SCORED BY THE SIMULATOR'S TRUTH: intra-robot closures given more than 1 m or 2 deg from the true relative pose "
      "of their two key poses";
  rep.add(p + "intra_closures_accepted", r.intra_accepted, "", false).note =
      "by the host's optimizer (odometry envelope); " + std::to_string(r.wrong_intra_accepted) + " of them wrong (truth)";
  for (const RealisticRunResult::IntraClosure& c : r.intra)
    spdlog::info("{}: intra closure {} -> {}: {:.2f} m / {:.2f} deg from truth, {}; host ATE so far {:.2f} m", p,
                 c.seq_a, c.seq_b, c.error_m, c.error_deg, c.accepted ? "accepted" : "rejected", c.host_ate_m);
  for (const RealisticRunResult::AteSoFar& a : r.ate_trace)
    spdlog::info("{}: after {} key poses: host ATE {:.2f} m, its odometry's {:.2f} m", p, a.keyposes, a.host_ate_m,
                 a.odom_ate_m);
  rep.add(p + "inter_transforms", r.inter_transforms, "", false).note = "given to the host's optimizer";
  rep.add(p + "wrong_transforms", r.wrong_inter, "", true, 0.0).note =
      "inter-robot transforms given more than 1 m or 2 deg from the least-squares alignment of the two own maps over "
      "the true objects both hold (or between maps sharing none)";
  rep.add(p + "wrong_transforms_at_place", r.wrong_inter_at_place, "", true, 0.0).note =
      "the same against the alignment over the true objects both maps hold within " +
      std::to_string(static_cast<int>(RealisticRunResult::kPlaceRadius)) +
      " m of the transform's inliers (bent maps sharing several places admit no one rigid alignment)";
  if (!r.place_error_m.empty())
    rep.add(p + "transform_vs_place_m.median", bench::median(r.place_error_m), "m").note = "against that alignment";
  if (!r.map_error_m.empty()) {
    rep.add(p + "transform_vs_maps_m.median", bench::median(r.map_error_m), "m").note = "against the maps' alignment";
    rep.add(p + "transform_vs_frames_m.median", bench::median(r.frame_error_m), "m").note =
        "against the robots' true start frames (drift included)";
  }
  rep.add(p + "landmarks", r.landmarks, "", false).note = "confirmed";
  rep.add(p + "false_landmarks", r.false_landmarks, "", false).note =
      "confirmed landmarks made mostly of false-object detections";
  rep.add(p + "duplicate_fraction", r.duplicate_fraction, "", true, 0.02).note =
      "confirmed landmarks beyond the first of one true object (scored by the simulator's object ids)";
  rep.add(p + "landmark_rmse_m", r.landmark_rmse_m, "m");
  rep.add(p + "place_cpu_s", r.place_cpu_s, "s").note = "every robot's loop closer, thread CPU";
}
// A long mission (forest tiles, makeForestReturnScenario or makeForestChainScenario) at one
// size: the scale names of BENCHMARKS.md.
void reportLong(bench::BenchReport& rep, int keyposes, const std::string& route, const ScenarioRunResult& r,
                bool background, double rate_hz) {
  const std::string rate = std::to_string(static_cast<int>(rate_hz));
  const std::string p = "backend." + std::to_string(keyposes) + ".";
  const std::string n = std::to_string(r.update_ms.size()) + " updates, one run (forest tiles, route " + route + ", " +
                        (background ? "full solves in the background, key poses at <= " + rate + " Hz while one runs"
                                    : "full solves inside updates") + ")";
  rep.add(p + "update_ms.median", bench::median(r.update_ms), "ms").note = n;
  rep.add(p + "update_ms.p99", bench::quantile(r.update_ms, 0.99), "ms").note = n;
  rep.add(p + "update_ms.max", bench::quantile(r.update_ms, 1.0), "ms", true, 50.0).note =
      n + ", loop closures included; target: issue 21";
  rep.add(p + "update_cpu_ms.max", bench::quantile(r.update_cpu_ms, 1.0), "ms").note =
      "thread CPU time of the slowest update (wall time on a shared machine includes waiting for a core)";
  rep.add(p + "full_solves", r.full_solves, "").note = "full-solve results taken into the estimate during updates";
  rep.add(p + "full_solve_ms.median", bench::median(r.full_solve_ms), "ms").note =
      std::string("wall time of each full solve taken in") + (background ? ", on the worker thread" : ", inside an update");
  rep.add(p + "full_solve_ms.max", bench::quantile(r.full_solve_ms, 1.0), "ms");
  rep.add(p + "loops_during_solve", r.loops_during_solve, "", false).note =
      "loop closures that arrived while a background solve ran";
  rep.add(p + "update_total_s", std::accumulate(r.update_ms.begin(), r.update_ms.end(), 0.0) / 1000.0, "s").note =
      "wall time inside the updates";
  rep.add(p + "update_cpu_total_s", std::accumulate(r.update_cpu_ms.begin(), r.update_cpu_ms.end(), 0.0) / 1000.0, "s")
      .note = "CPU time of the updating thread";
  rep.add(p + "process_cpu_s", processCpuSeconds(), "s").note =
      "CPU time of every thread of the run (scenario simulation, updates, background solves, final solve)";
  rep.add(p + "final_solve_ms", r.final_solve_ms, "ms").note = "full solve to convergence after the last update";
  rep.add(p + "ate_m", r.ate_m, "m").note = "after the final solve";
  rep.add(p + "live_ate_m", r.live_ate_m, "m").note = "the estimate after the last update, before the final solve";
  rep.add(p + "odom_ate_m", r.odom_ate_m, "m");
  rep.add(p + "ate_ratio", r.ate_m / std::max(1e-9, r.odom_ate_m), "", true, 0.15).note =
      "ATE / odometry ATE, after the final solve; target: issue 21";
  rep.add(p + "live_ate_ratio", r.live_ate_m / std::max(1e-9, r.odom_ate_m), "", true, 0.15).note =
      "ATE / odometry ATE of the estimate published after the last update";
  rep.add(p + "live_max_step_error_m", r.live_max_step_error_m, "m").note =
      "largest error of an estimated key-pose step (consecutive key poses) in the live estimate, against the truth";
  rep.add(p + "duplicate_fraction", r.duplicate_fraction, "", true, 0.02).note =
      "confirmed landmarks duplicating another's true object (simulator's associations), over confirmed landmarks";
  rep.add(p + "landmarks", r.landmarks, "", false).note = std::to_string(r.true_landmarks_seen) + " true ones seen";
  rep.add(p + "loop_closures", r.loop_closures, "", false);
  rep.add(p + "rss_mb", peakRssMb(), "MB").note = "peak resident set of the process";
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Back-end benchmark: incremental update time, batch baseline, ATE and landmarks per scenario; for KITTI\n"
               "05/07 also each robot's object map size as shared (KB) against its raw scans (MB)"};
  app::CommonOptions common;
  std::string json, config_path = std::string(SLIDE_SOURCE_DIR) + "/config/backend.yaml";
  std::string data_dir = SLIDE_DATA_DIR;
  std::vector<std::string> only;
  app.add_option("--json", json, "write the results as JSON (BENCHMARKS.md) to this file");
  app.add_option("--config", config_path, "back-end parameters (YAML)");
  app.add_option("--data", data_dir, "folder of the shared real data (KITTI poses and poles)");
  app.add_option("--scenario", only,
                 "run only these scenarios (indoor urban forest kitti05 kitti07, idealised; each with _realistic "
                 "appended: the realistic case)");
  graph_scenario::ScenarioRealism realism{0.2, 0.15, 2, 0.1, 2.0, 0.01};
  app.add_option("--miss", realism.miss_rate, "realistic cases: missed-detection rate")->capture_default_str();
  app.add_option("--clutter", realism.clutter_fraction, "realistic cases: fraction of detections that are false objects")
      ->capture_default_str();
  app.add_option("--confusion", realism.confusion_rate, "realistic cases: class-confusion rate (within a shape)")
      ->capture_default_str();
  app.add_option("--noise-scale", realism.noise_scale,
                 "realistic cases: applied noise over the sigmas the estimator is given")
      ->capture_default_str();
  app.add_option("--scale-error", realism.odom_scale_error,
                 "realistic cases: each robot's odometry reads distance wrong by one factor, 1 + this x N(0,1) "
                 "(0: odometry with white noise only)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.19));
  std::uint32_t seed = 0;
  app.add_option("--seed", seed,
                 "simulation seed of the KITTI scenarios and of the realistic cases' detections (0: their defaults, 5 "
                 "and 17): run several to see the spread")
      ->capture_default_str();
  int long_keyposes = 0;
  bool background_solves = false;
  double rate_hz = 10;
  std::string route = "return";
  double final_seconds = 0;
  app.add_option("--keyposes", long_keyposes,
                 "instead: one long mission of this many key poses (forest tiles chained), named backend.<N>.*; "
                 "run one size per process (the figures include the peak RSS); full solves inside the updates "
                 "unless --background-solves; logs the live estimate's ATE every 500 key poses (and after every "
                 "full solve at --log-level debug)");
  app.add_option("--rate", rate_hz,
                 "long mission: key poses arrive at most this often while a background solve runs (1.43 m apart: "
                 "10 Hz is 14 m/s, faster than any of the team's robots)")
      ->capture_default_str();
  app.add_option("--route", route,
                 "long mission: 'return' drives out through the tiles and back to the start (revisits, loop closures "
                 "all the way back); 'chain' drives the tiles one after the other, never returning")
      ->check(CLI::IsMember({"return", "chain"}))
      ->capture_default_str();
  app.add_option("--final-seconds", final_seconds,
                 "long mission: bound the final solve to about this many seconds (0: to convergence)")
      ->capture_default_str();
  app.add_flag("--background-solves", background_solves,
               "long mission: full solves on a worker thread, as slide-optimizer does by default (the other "
               "scenarios always solve inside the updates)");
  app::addCommonOptions(app, common);
  return app::runApp(app, common, argc, argv, [&]() {
    backend::BackendConfig cfg = backend::loadBackendConfig(config_path);
    bench::BenchReport rep("backend");
    if (long_keyposes > 0) {
      cfg.background_solves = background_solves;
      const graph_scenario::GraphScenario s = route == "chain"
                                                  ? graph_scenario::makeForestChainScenario(long_keyposes)
                                                  : graph_scenario::makeForestReturnScenario(long_keyposes);
      spdlog::info("long mission ({}): {} key poses, {} landmarks", s.name, s.robots[0].bundles.size(), s.landmarks.size());
      reportLong(rep, long_keyposes, route, runScenario(s, cfg, false, rate_hz, final_seconds, 500), cfg.background_solves, rate_hz);
      rep.printTable(std::cout);
      if (!json.empty()) rep.writeJson(json);
      return 0;
    }
    auto wanted = [&](const std::string& s) { return only.empty() || std::find(only.begin(), only.end(), s) != only.end(); };
    const place::LoopCloserParams closer =
        place::loadLoopCloserParams(ConfigNode::load(std::string(SLIDE_SOURCE_DIR) + "/config/loop_closer.yaml"));
    const ClassTable classes = ClassTable::loadDefault();
    auto run = [&](const std::string& name, const graph_scenario::GraphScenario& s, const Targets& t) {
      if (wanted(name)) {
        spdlog::info("scenario {}: {} robots, {} landmarks", name, s.robots.size(), s.landmarks.size());
        report(rep, name, runScenario(s, cfg), t);
      }
      if (wanted(name + "_realistic")) {
        spdlog::info("scenario {}_realistic ({})", name, realism.describe());
        reportRealistic(rep, name, runRealistic(graph_scenario::withRealism(s, realism, classes, seed ? seed : 17), cfg, closer), realism,
                        t.paper_ate);
      }
    };
    auto any = [&](const std::string& name) { return wanted(name) || wanted(name + "_realistic"); };
    if (any("indoor"))
      run("indoor", graph_scenario::makeIndoorScenario(),
          {0.5, 4.0, std::nullopt, "iSAM2 anchor (same machine): 0.5 ms median, 3-4 ms p99"});
    if (any("urban"))
      run("urban", graph_scenario::makeUrbanScenario(),
          {0.5, 10.0, std::nullopt, "iSAM2 anchor: 0.43 ms median, 14 ms p99"});
    if (any("forest"))
      run("forest", graph_scenario::makeForestScenario(),
          {1.0, 20.0, std::nullopt, "iSAM2 anchor: 0.9 ms median, ~90 ms p99, ~110 ms max, ~8 s total"});
    for (const std::string seq : {"05", "07"}) {
      if (!any("kitti" + seq)) continue;
      const graph_scenario::GraphScenario s = graph_scenario::makeKittiScenario(
          "kitti" + seq, data_dir + "/kitti/poses/" + seq + ".txt", data_dir + "/kitti/poles/" + seq + ".csv", 3, 2.0, seed ? seed : 5);
      run("kitti" + seq, s, {std::nullopt, std::nullopt, seq == "05" ? 0.998 : 0.962, "3 robots, paper ATE in 'paper'"});
      if (!wanted("kitti" + seq)) continue;
      const double points = meanPointsPerScan(data_dir + "/semantickitti/sequences/08/velodyne");
      const std::vector<Pose> lidar = io::kittiLidarPoses(io::readKittiPoses(data_dir + "/kitti/poses/" + seq + ".txt"),
                                                          io::kittiVeloToCamTr0410());
      reportMapSizes(rep, "kitti" + seq, robotMapSizes(s, cfg, lidar, points), points);
    }
    rep.printTable(std::cout);
    if (!json.empty()) rep.writeJson(json);
    return 0;
  });
}
