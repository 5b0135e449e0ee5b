// slide-bench-place: place recognition figures (BENCHMARKS.md, suite "place").
#include <spdlog/spdlog.h>

#include <iostream>
#include <set>

#include "app/app.h"
#include "bench/report.h"
#include "bench/stats.h"
#include "config/config.h"
#include "hetero.h"
#include "place/loop_closer_config.h"
#include "realistic.h"
#include "scale.h"
#include "scenarios.h"

using namespace slide;
using namespace slide::bench_place;

namespace {
struct Paper {
  std::optional<double> graph_ms, match_ms, trans, yaw;
  std::optional<double> target_graph_ms, target_match_ms, target_trans, target_yaw;
  std::string graph_ms_note, match_ms_note, err_note;
};

Paper paperFor(const std::string& name) {
  Paper p;
  if (name == "indoor") {
    p.graph_ms = 25, p.target_graph_ms = 5, p.graph_ms_note = "paper 22-28 ms";
  } else if (name == "urban") {
    p.graph_ms = 90.5, p.target_graph_ms = 10, p.graph_ms_note = "paper 86-95 ms";
  } else if (name == "forest") {
    p.graph_ms = 307.5, p.target_graph_ms = 30, p.graph_ms_note = "paper 209-406 ms";
    p.match_ms = 1600, p.target_match_ms = 200, p.match_ms_note = "paper 1.1-2.1 s";
  } else if (name == "kitti05" || name == "kitti07") {
    p.trans = 0.0625, p.yaw = 0.081, p.target_trans = 0.05, p.target_yaw = 0.1;
    p.err_note = "paper 0.03-0.095 m, 0.065-0.097 deg";
  }
  return p;
}

void report(bench::BenchReport& rep, const Scenario& s, place::PlaceMethod m, const MethodFigures& f, int repeats) {
  const std::string prefix = s.name + "." + place::methodName(m) + ".";
  const Paper p = paperFor(s.name);
  const bool graph = m == place::PlaceMethod::SlideGraph;
  // These scenarios' maps are rigid copies of the truth with independent noise and drops (no
  // drift, no false or confused objects): the realistic cases are runRealistic's.
  const std::string of = "IDEALISED input (rigid copies); median over " + std::to_string(f.correct) + " correct of " +
                         std::to_string(f.overlapping) + " pairs";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto& t = rep.add(prefix + "trans_err_m", f.trans_err.empty() ? nan : bench::median(f.trans_err), "m", true,
                    p.target_trans, p.trans);
  t.note = of + (p.err_note.empty() ? "" : "; " + p.err_note);
  auto& y = rep.add(prefix + "yaw_err_deg", f.yaw_err.empty() ? nan : bench::median(f.yaw_err), "deg", true,
                    p.target_yaw, p.yaw);
  y.note = t.note;
  auto& ms = rep.add(prefix + "ms", bench::median(f.cpu_ms), "ms", true, graph ? p.target_graph_ms : p.target_match_ms,
                     graph ? p.graph_ms : p.match_ms);
  ms.note = "thread CPU time, median of " + std::to_string(f.ms.size()) + " runs (" + std::to_string(repeats) + " per pair)" +
            ((graph ? p.graph_ms_note : p.match_ms_note).empty() ? "" : "; " + (graph ? p.graph_ms_note : p.match_ms_note));
  rep.add(prefix + "ms.p90", bench::quantile(f.cpu_ms, 0.9), "ms").note = "thread CPU time, 90th percentile";
  rep.add(prefix + "wall_ms", bench::median(f.ms), "ms").note =
      "wall time, median (inflated when the machine is loaded)";
  for (const auto& [stage, v] : f.stage_cpu_ms)
    rep.add(prefix + "stage_ms." + stage, bench::median(v), "ms").note = "thread CPU time per run, median";
  rep.add(prefix + "recall", f.overlapping ? double(f.correct) / f.overlapping : nan, "", false, 1.0).note =
      "correct transforms / overlapping pairs (" + std::to_string(f.missed) + " missed, " + std::to_string(f.wrong) + " wrong)";
  rep.add(prefix + "wrong", f.wrong + f.false_positives, "", true, 0.0).note =
      "wrong transforms on overlapping pairs plus any on " + std::to_string(f.disjoint) + " disjoint pairs";
}
// One figure per method over the trials: found and correct (within 2 m and 10 deg: good enough
// to seed a merge) as fractions, errors as medians over the trials that found a transform.
void reportHetero(bench::BenchReport& rep, const HeteroSpec& spec, const std::vector<HeteroFigures>& trials,
                  int repeats) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const bool lidar_rgbd = spec.name == "hetero_lidar_rgbd";
  const double n = static_cast<double>(trials.size());
  const std::string of = std::to_string(trials.size()) + " worlds (seeds " + std::to_string(spec.seed) + "..." +
                         std::to_string(spec.seed + trials.size() - 1) + ")";
  for (place::PlaceMethod m : {place::PlaceMethod::SlideGraph, place::PlaceMethod::SlideMatch}) {
    std::vector<double> t, y, ms;
    int found = 0, correct = 0;
    std::string reasons;
    for (const HeteroFigures& f : trials) {
      const HeteroMethod& h = m == place::PlaceMethod::SlideGraph ? f.slidegraph : f.slidematch;
      ms.push_back(h.cpu_ms);
      if (!h.found) {
        reasons += (reasons.empty() ? "" : "; ") + h.reason;
        continue;
      }
      ++found;
      correct += h.trans_err_m < 2.0 && h.yaw_err_deg < 10.0;
      t.push_back(h.trans_err_m);
      y.push_back(h.yaw_err_deg);
    }
    const std::string prefix = spec.name + "." + place::methodName(m) + ".";
    // Paper: LiDAR-RGBD 0.54-0.58 m, 2-4 deg (the paper does not split it by method);
    // aerial-ground SlideMatch 0.245 m, SlideGraph fails.
    std::optional<double> paper_t, paper_y, paper_found;
    std::string paper_note;
    if (lidar_rgbd) {
      paper_t = 0.56, paper_y = 3.0, paper_found = 1.0, paper_note = "paper 0.54-0.58 m, 2-4 deg";
    } else if (m == place::PlaceMethod::SlideMatch) {
      paper_t = 0.245, paper_found = 1.0, paper_note = "paper 0.245 m";
    } else {
      paper_found = 0.0, paper_note = "paper: SlideGraph fails";
    }
    std::string errs;
    for (std::size_t i = 0; i < t.size(); ++i)
      errs += (i ? ", " : "") + fmt::format("{:.2f} m / {:.1f} deg", t[i], y[i]);
    rep.add(prefix + "found", found / n, "", false, std::nullopt, paper_found).note =
        std::to_string(found) + " of " + of + (reasons.empty() ? "" : "; none: " + reasons) + "; " + paper_note;
    rep.add(prefix + "correct", correct / n, "", false).note =
        std::to_string(correct) + " of " + std::to_string(trials.size()) + " within 2 m and 10 deg of the truth";
    rep.add(prefix + "trans_err_m", t.empty() ? nan : bench::median(t), "m", true, std::nullopt, paper_t).note =
        (t.empty() ? "none found" : "median over the " + std::to_string(t.size()) + " found: " + errs) + "; " + paper_note;
    rep.add(prefix + "yaw_err_deg", y.empty() ? nan : bench::median(y), "deg", true, std::nullopt, paper_y).note =
        t.empty() ? "none found" : "median over the found";
    rep.add(prefix + "ms", bench::median(ms), "ms").note =
        "thread CPU time, median over the worlds of the median of " + std::to_string(repeats) + " runs";
  }
  double oa = 0, ob = 0, ta = 0, tb = 0, sh = 0, ca = 0, cb = 0, fa = 0, fb = 0, wall = 0, ea = 0, eb = 0;
  for (const HeteroFigures& f : trials) {
    oa += f.objects_a / n, ob += f.objects_b / n, ta += f.true_a / n, tb += f.true_b / n, sh += f.shared / n;
    ea += f.err_a / n, eb += f.err_b / n;
    ca += f.map_cpu_s_a / n, cb += f.map_cpu_s_b / n, fa += f.frames_a / n, fb += f.frames_b / n, wall += f.wall_s;
  }
  rep.add(spec.name + ".objects_a", oa, "", false).note =
      spec.sensor_a + ", mean over the worlds; " + fmt::format("{:.1f}", ta) + " on a true object of their class";
  rep.add(spec.name + ".objects_b", ob, "", false).note =
      spec.sensor_b + ", mean; " + fmt::format("{:.1f}", tb) + " on a true object of their class";
  rep.add(spec.name + ".object_err_m_a", ea, "m").note =
      "median horizontal distance of A's landmarks to their true object (world frame, true odometry origin), mean";
  rep.add(spec.name + ".object_err_m_b", eb, "m").note = "the same for B";
  rep.add(spec.name + ".shared_objects", sh, "", false).note = "true objects in both maps, mean";
  rep.add(spec.name + ".map_cpu_s_a", ca, "s").note =
      fmt::format("mean over the worlds; {:.0f} frames: simulation + front-end + back-end, CPU", fa);
  rep.add(spec.name + ".map_cpu_s_b", cb, "s").note = fmt::format("mean; {:.0f} frames", fb);
  rep.add(spec.name + ".wall_s", wall, "s").note = "all worlds: simulation, mapping both robots, place recognition";
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Place-recognition benchmark: SlideGraph and SlideMatch on indoor, urban, forest, KITTI 05/07, the\n"
               "real SlideSLAM maps and two heterogeneous simulated teams (LiDAR + RGBD indoors, aerial + ground RGBD\n"
               "over a parking lot) mapped through the front-end and back-end.\nPrints a table; --json writes the BENCHMARKS.md JSON (suite 'place').",
               "slide-bench-place"};
  app::CommonOptions common;
  app::addCommonOptions(app, common);
  std::string json, data = SLIDE_DATA_DIR, config_path;
  int repeats = 3, hetero_worlds = 3;
  unsigned seed = 1;
  std::vector<std::string> only;
  std::string dump;
  app.add_option("--json", json, "Write the results as JSON to this file");
  app.add_option("--data", data, "Folder of the shared data sets")->capture_default_str();
  app.add_option("--config", config_path, "Place-recognition parameters (default: config/place.yaml)");
  app.add_option("--repeats", repeats, "Timed runs per pair")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "Seed of the procedural worlds and noise")->capture_default_str();
  app.add_option("--only", only, "Scenarios to run (default all): indoor urban forest kitti05 kitti07 parking_real indoor_real indoor_aliased\n"
                 "hetero_lidar_rgbd hetero_aerial_ground realistic; 'scale' (maps of 1,000-30,000 objects, long: suite\n"
                 "place_scale) runs only when named");
  std::vector<int> scale_sizes{1000, 10000, 30000};
  std::vector<std::string> scale_conditions{"target", "mild"};
  app.add_option("--scale-sizes", scale_sizes, "Objects per map of the scale cases")->capture_default_str();
  app.add_option("--scale-conditions", scale_conditions, "Conditions of the scale cases (target, mild, harsh)")
      ->capture_default_str();
  std::vector<std::string> realistic_worlds;
  app.add_option("--realistic-worlds", realistic_worlds,
                 "Worlds of the realistic cases (default all): forest longleaf spruces finpines urban indoor indoor_repeated forest_large");
  app.add_option("--hetero-worlds", hetero_worlds, "Worlds (seeds seed, seed+1, ...) per heterogeneous case")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--dump", dump, "Write every pair's maps as DIR/<scenario>_<k>_{a,b}.txt (for ./slide match; realistic pairs as realistic_<world>_<condition>_<k>_{a,b}.txt) and log the truth");
  return app::runApp(app, common, argc, argv, [&]() {
    const place::PlaceConfig config =
        config_path.empty() ? place::loadDefaultPlaceConfig() : place::loadPlaceConfig(config_path);
    const std::set<std::string> want(only.begin(), only.end());
    auto wanted = [&](const std::string& n) { return want.empty() || want.count(n); };
    std::vector<Scenario> scenarios;
    if (wanted("indoor")) scenarios.push_back(indoorScenario(seed));
    if (wanted("urban")) scenarios.push_back(urbanScenario(seed));
    if (wanted("forest")) scenarios.push_back(forestScenario(seed, 5, 20));
    if (wanted("kitti05")) scenarios.push_back(kittiScenario(data, "05", seed));
    if (wanted("kitti07")) scenarios.push_back(kittiScenario(data, "07", seed));
    if (wanted("parking_real")) scenarios.push_back(realScenario(data, "parking", seed));
    if (wanted("indoor_real")) scenarios.push_back(realScenario(data, "indoor", seed));

    if (!dump.empty()) {
      for (const Scenario& s : scenarios)
        for (std::size_t k = 0; k < s.pairs.size(); ++k) {
          const std::string stem = dump + "/" + s.name + "_" + std::to_string(k);
          writeLandmarks(stem + "_a.txt", s.pairs[k].a.lms);
          writeLandmarks(stem + "_b.txt", s.pairs[k].b.lms);
          const Eigen::Vector4d t = xyzYawOf(truthBetween(s.pairs[k].a, s.pairs[k].b));
          spdlog::info("{}: truth x {:.3f} y {:.3f} z {:.3f} yaw {:.3f} deg{}", stem, t[0], t[1], t[2], t[3] * 180 / M_PI,
                       s.pairs[k].overlapping ? "" : " (disjoint: no transform expected)");
        }
    }
    const bool scale_only = want.size() == 1 && want.count("scale");
    bench::BenchReport rep(scale_only ? "place_scale" : "place");
    for (const Scenario& s : scenarios) {
      std::size_t na = 0, nb = 0, shared = 0, overlapping = 0;
      for (const PairCase& c : s.pairs) {
        na += c.a.lms.size(), nb += c.b.lms.size();
        if (c.overlapping) shared += sharedLandmarks(c.a, c.b), ++overlapping;
      }
      spdlog::info("{}: {} pairs, mean {} x {} landmarks, {} shared per overlapping pair; {}", s.name, s.pairs.size(),
                   na / s.pairs.size(), nb / s.pairs.size(), shared / std::max<std::size_t>(1, overlapping), s.description);
      int fp = 0;
      for (place::PlaceMethod m : {place::PlaceMethod::SlideGraph, place::PlaceMethod::SlideMatch}) {
        const MethodFigures f = runScenario(s, m, config, repeats);
        report(rep, s, m, f, repeats);
        fp += f.false_positives + f.wrong;
        if (s.name == "forest" && m == place::PlaceMethod::SlideGraph) {
          rep.add("forest.clipper.peak_mb", f.peak_bytes / 1e6, "MB").note =
              "largest consistency graph + solver vectors; a dense m x m double matrix would take " +
              std::to_string(static_cast<int>(8.0 * f.max_associations * f.max_associations / 1e6)) + " MB (m = " +
              std::to_string(f.max_associations) + ")";
        }
      }
      if (s.name == "forest") {
        rep.add("forest.false_positives", fp, "", true, 0.0).note =
            "both methods: transforms on disjoint pairs plus wrong ones on overlapping pairs";
        const ClipperStress cs = clipperStress(s.pairs.front(), 40, config.slidegraph.clipper, seed);
        const std::string m = std::to_string(cs.associations);
        rep.add("forest.clipper.stress.associations", cs.associations, "").note =
            std::to_string(cs.true_associations) + " true, the rest random (40 per landmark of B)";
        rep.add("forest.clipper.stress.peak_mb", cs.peak_bytes / 1e6, "MB").note =
            std::to_string(cs.edges) + " consistent pairs; a dense m x m double matrix would take " +
            std::to_string(static_cast<long>(8.0 * cs.associations * cs.associations / 1e6)) + " MB";
        rep.add("forest.clipper.stress.ms", cs.ms, "ms").note = "thread CPU time, graph + solve, one run";
        rep.add("forest.clipper.stress.precision", cs.selected ? double(cs.selected_true) / cs.selected : 0, "", false).note =
            std::to_string(cs.selected_true) + " true of " + std::to_string(cs.selected) + " selected";
        rep.add("forest.clipper.stress.recall", double(cs.selected_true) / std::max<std::size_t>(1, cs.true_associations), "",
                false);
      }
      if (s.name == "parking_real" || s.name == "indoor_real") {
        const std::string set = s.name == "parking_real" ? "parking" : "indoor";
        for (place::PlaceMethod m : {place::PlaceMethod::SlideGraph, place::PlaceMethod::SlideMatch}) {
          const Cycle c = realCycle(data, set, m, config);
          const std::string prefix = s.name + "." + place::methodName(m) + ".cycle_";
          const double nan = std::numeric_limits<double>::quiet_NaN();
          rep.add(prefix + "trans_m", c.ok ? c.trans_m : nan, "m").note =
              c.ok ? "|T01 T12 T20| between the three robots' real maps" : "no cycle: " + c.why;
          rep.add(prefix + "yaw_deg", c.ok ? c.yaw_deg : nan, "deg").note = c.ok ? "" : "no cycle";
        }
      }
    }
    if (wanted("indoor_aliased")) {
      for (place::PlaceMethod m : {place::PlaceMethod::SlideGraph, place::PlaceMethod::SlideMatch}) {
        AliasFigures a;
        for (unsigned w = 0; w < 5; ++w) {  // five worlds, 30 re-mappings each
          const AliasFigures one = aliasedRooms(seed + w, m, config, place::ConsensusParams{}, 30);
          a.attempts += one.attempts, a.raw_found += one.raw_found, a.raw_wrong += one.raw_wrong;
          a.published += one.published, a.published_wrong += one.published_wrong;
        }
        const std::string prefix = std::string("indoor_aliased.") + place::methodName(m) + ".";
        rep.add(prefix + "raw_wrong_fraction", a.raw_found ? double(a.raw_wrong) / a.raw_found : 0, "", true).note =
            std::to_string(a.raw_wrong) + " wrong of " + std::to_string(a.raw_found) + " found in " +
            std::to_string(a.attempts) + " attempts (5 worlds of two identical rooms)";
        rep.add(prefix + "published_wrong_fraction", a.published ? double(a.published_wrong) / a.published : 0, "", true)
            .note = std::to_string(a.published_wrong) + " wrong of " + std::to_string(a.published) +
                    " published by the consensus filter";
      }
    }
    if (want.count("scale")) runScale(rep, config, seed, scale_sizes, scale_conditions);
    if (wanted("realistic")) {
      // The loop closer's own consensus settings (config/loop_closer.yaml).
      const place::ConsensusParams consensus =
          place::loadLoopCloserParams(ConfigNode::load(std::string(SLIDE_SOURCE_DIR) + "/config/loop_closer.yaml"))
              .consensus;
      runRealistic(rep, config, consensus, seed, realistic_worlds, dump);
    }
    for (const HeteroSpec& h : {heteroLidarRgbd(seed), heteroAerialGround(seed)}) {
      if (!wanted(h.name)) continue;
      spdlog::info("{}: {}", h.name, h.description);
      std::vector<HeteroFigures> trials;
      for (int k = 0; k < hetero_worlds; ++k) {
        HeteroSpec one = h;
        one.seed = h.seed + k;
        trials.push_back(runHetero(one, config, repeats));
        const HeteroFigures& f = trials.back();
        spdlog::info("{} seed {}: maps of {} and {} objects ({} true objects in both) in {:.1f} s; SlideGraph {}, SlideMatch {}",
                     h.name, one.seed, f.objects_a, f.objects_b, f.shared, f.wall_s,
                     f.slidegraph.found ? fmt::format("{:.2f} m {:.1f} deg", f.slidegraph.trans_err_m, f.slidegraph.yaw_err_deg) : "none",
                     f.slidematch.found ? fmt::format("{:.2f} m {:.1f} deg", f.slidematch.trans_err_m, f.slidematch.yaw_err_deg) : "none");
      }
      reportHetero(rep, h, trials, repeats);
    }
    rep.printTable(std::cout);
    if (!json.empty()) rep.writeJson(json);
    return 0;
  });
}
