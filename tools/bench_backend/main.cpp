// slide-bench-backend: per-key-pose update time, batch baseline and accuracy of the back-end
// on the indoor, urban, forest and KITTI 05/07 scenarios (BENCHMARKS.md names).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <iostream>
#include <numeric>

#include "app/app.h"
#include "backend/backend_config.h"
#include "bench/report.h"
#include "bench/stats.h"
#include "io/kitti_poses.h"
#include "map_size.h"
#include "scenario_run.h"

using namespace slide;

namespace {
struct Targets {
  std::optional<double> median, p99;
  std::optional<double> paper_ate;
  std::string anchor;  // iSAM2 / paper timing figures quoted by the issue
};

void report(BenchReport& rep, const std::string& name, const ScenarioRunResult& r, const Targets& t) {
  const std::string n = std::to_string(r.update_ms.size()) + " updates, one run";
  rep.add(name + ".update_ms.median", median(r.update_ms), "ms", true, t.median).note = n + "; " + t.anchor;
  rep.add(name + ".update_ms.p99", quantile(r.update_ms, 0.99), "ms", true, t.p99).note =
      n + ", loop closures and merges included; " + t.anchor;
  rep.add(name + ".update_ms.max", quantile(r.update_ms, 1.0), "ms");
  rep.add(name + ".update_cpu_ms.median", median(r.update_cpu_ms), "ms").note = "thread CPU time of the same updates";
  rep.add(name + ".update_cpu_ms.p99", quantile(r.update_cpu_ms, 0.99), "ms");
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
void reportMapSizes(BenchReport& rep, const std::string& name, const std::vector<RobotMapSize>& sizes, double points) {
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
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Back-end benchmark: incremental update time, batch baseline, ATE and landmarks per scenario; for KITTI\n"
               "05/07 also each robot's object map size as shared (KB) against its raw scans (MB)"};
  CommonOptions common;
  std::string json, config_path = std::string(SLIDE_SOURCE_DIR) + "/config/backend.yaml";
  std::string data_dir = SLIDE_DATA_DIR;
  std::vector<std::string> only;
  app.add_option("--json", json, "write the results as JSON (BENCHMARKS.md) to this file");
  app.add_option("--config", config_path, "back-end parameters (YAML)");
  app.add_option("--data", data_dir, "folder of the shared real data (KITTI poses and poles)");
  app.add_option("--scenario", only, "run only these scenarios (indoor urban forest kitti05 kitti07)");
  addCommonOptions(app, common);
  return runApp(app, common, argc, argv, [&]() {
    const BackendConfig cfg = loadBackendConfig(config_path);
    BenchReport rep("backend");
    auto wanted = [&](const std::string& s) { return only.empty() || std::find(only.begin(), only.end(), s) != only.end(); };
    auto run = [&](const std::string& name, const Scenario& s, const Targets& t) {
      spdlog::info("scenario {}: {} robots, {} landmarks", name, s.robots.size(), s.landmarks.size());
      report(rep, name, runScenario(s, cfg), t);
    };
    if (wanted("indoor"))
      run("indoor", makeIndoorScenario(),
          {0.5, 4.0, std::nullopt, "iSAM2 anchor (same machine): 0.5 ms median, 3-4 ms p99"});
    if (wanted("urban"))
      run("urban", makeUrbanScenario(), {0.5, 10.0, std::nullopt, "iSAM2 anchor: 0.43 ms median, 14 ms p99"});
    if (wanted("forest"))
      run("forest", makeForestScenario(),
          {1.0, 20.0, std::nullopt, "iSAM2 anchor: 0.9 ms median, ~90 ms p99, ~110 ms max, ~8 s total"});
    for (const std::string seq : {"05", "07"}) {
      if (!wanted("kitti" + seq)) continue;
      const Scenario s = makeKittiScenario("kitti" + seq, data_dir + "/kitti/poses/" + seq + ".txt",
                                           data_dir + "/kitti/poles/" + seq + ".csv", 3);
      run("kitti" + seq, s, {std::nullopt, std::nullopt, seq == "05" ? 0.998 : 0.962, "3 robots, paper ATE in 'paper'"});
      const double points = meanPointsPerScan(data_dir + "/semantickitti/sequences/08/velodyne");
      const std::vector<Pose> lidar =
          kittiLidarPoses(readKittiPoses(data_dir + "/kitti/poses/" + seq + ".txt"), kittiVeloToCamTr0410());
      reportMapSizes(rep, "kitti" + seq, robotMapSizes(s, cfg, lidar, points), points);
    }
    rep.printTable(std::cout);
    if (!json.empty()) rep.writeJson(json);
    return 0;
  });
}
