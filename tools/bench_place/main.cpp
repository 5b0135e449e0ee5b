// slide-bench-place: place recognition figures (BENCHMARKS.md, suite "place").
#include <spdlog/spdlog.h>

#include <iostream>
#include <set>

#include "app/app.h"
#include "bench/report.h"
#include "bench/stats.h"
#include "mapio/object_map_text.h"
#include "scenarios.h"

using namespace slide;
using namespace slide::bench;

namespace {
void writeLandmarks(const std::string& path, const std::vector<Landmark>& lms, const ClassTable& classes) {
  ObjectMap map;
  for (const Landmark& l : lms) map.add(objectFromCentre(l.class_id, l.p, l.size, classes));
  writeObjectMapText(path, map, classes);
}

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

void report(BenchReport& rep, const Scenario& s, PlaceMethod m, const MethodFigures& f, int repeats) {
  const std::string prefix = s.name + "." + methodName(m) + ".";
  const Paper p = paperFor(s.name);
  const bool graph = m == PlaceMethod::SlideGraph;
  const std::string of = "median over " + std::to_string(f.correct) + " correct of " + std::to_string(f.overlapping) + " pairs";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto& t = rep.add(prefix + "trans_err_m", f.trans_err.empty() ? nan : median(f.trans_err), "m", true, p.target_trans, p.trans);
  t.note = of + (p.err_note.empty() ? "" : "; " + p.err_note);
  auto& y = rep.add(prefix + "yaw_err_deg", f.yaw_err.empty() ? nan : median(f.yaw_err), "deg", true, p.target_yaw, p.yaw);
  y.note = t.note;
  auto& ms = rep.add(prefix + "ms", median(f.cpu_ms), "ms", true, graph ? p.target_graph_ms : p.target_match_ms,
                     graph ? p.graph_ms : p.match_ms);
  ms.note = "thread CPU time, median of " + std::to_string(f.ms.size()) + " runs (" + std::to_string(repeats) + " per pair)" +
            ((graph ? p.graph_ms_note : p.match_ms_note).empty() ? "" : "; " + (graph ? p.graph_ms_note : p.match_ms_note));
  rep.add(prefix + "ms.p90", quantile(f.cpu_ms, 0.9), "ms").note = "thread CPU time, 90th percentile";
  rep.add(prefix + "wall_ms", median(f.ms), "ms").note = "wall time, median (inflated when the machine is loaded)";
  for (const auto& [stage, v] : f.stage_cpu_ms) rep.add(prefix + "stage_ms." + stage, median(v), "ms").note = "thread CPU time per run, median";
  rep.add(prefix + "recall", f.overlapping ? double(f.correct) / f.overlapping : nan, "", false, 1.0).note =
      "correct transforms / overlapping pairs (" + std::to_string(f.missed) + " missed, " + std::to_string(f.wrong) + " wrong)";
  rep.add(prefix + "wrong", f.wrong + f.false_positives, "", true, 0.0).note =
      "wrong transforms on overlapping pairs plus any on " + std::to_string(f.disjoint) + " disjoint pairs";
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Place-recognition benchmark: SlideGraph and SlideMatch on indoor, urban, forest, KITTI 05/07 and the\n"
               "real SlideSLAM maps. Prints a table; --json writes the BENCHMARKS.md JSON (suite 'place').",
               "slide-bench-place"};
  CommonOptions common;
  addCommonOptions(app, common);
  std::string json, data = SLIDE_DATA_DIR, config_path;
  int repeats = 3;
  unsigned seed = 1;
  std::vector<std::string> only;
  std::string dump;
  app.add_option("--json", json, "Write the results as JSON to this file");
  app.add_option("--data", data, "Folder of the shared data sets")->capture_default_str();
  app.add_option("--config", config_path, "Place-recognition parameters (default: config/place.yaml)");
  app.add_option("--repeats", repeats, "Timed runs per pair")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "Seed of the procedural worlds and noise")->capture_default_str();
  app.add_option("--only", only, "Scenarios to run (default all): indoor urban forest kitti05 kitti07 parking_real indoor_real indoor_aliased");
  app.add_option("--dump", dump, "Write every pair's maps as DIR/<scenario>_<k>_{a,b}.txt (for ./slide match)");
  return runApp(app, common, argc, argv, [&]() {
    const PlaceConfig config = config_path.empty() ? loadDefaultPlaceConfig() : loadPlaceConfig(config_path);
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
      const ClassTable classes = ClassTable::loadDefault();
      for (const Scenario& s : scenarios)
        for (std::size_t k = 0; k < s.pairs.size(); ++k) {
          const std::string stem = dump + "/" + s.name + "_" + std::to_string(k);
          writeLandmarks(stem + "_a.txt", s.pairs[k].a.lms, classes);
          writeLandmarks(stem + "_b.txt", s.pairs[k].b.lms, classes);
          const Eigen::Vector4d t = xyzYawOf(truthBetween(s.pairs[k].a, s.pairs[k].b));
          spdlog::info("{}: truth x {:.3f} y {:.3f} z {:.3f} yaw {:.3f} deg{}", stem, t[0], t[1], t[2], t[3] * 180 / M_PI,
                       s.pairs[k].overlapping ? "" : " (disjoint: no transform expected)");
        }
    }
    BenchReport rep("place");
    for (const Scenario& s : scenarios) {
      std::size_t na = 0, nb = 0, shared = 0, overlapping = 0;
      for (const PairCase& c : s.pairs) {
        na += c.a.lms.size(), nb += c.b.lms.size();
        if (c.overlapping) shared += sharedLandmarks(c.a, c.b), ++overlapping;
      }
      spdlog::info("{}: {} pairs, mean {} x {} landmarks, {} shared per overlapping pair; {}", s.name, s.pairs.size(),
                   na / s.pairs.size(), nb / s.pairs.size(), shared / std::max<std::size_t>(1, overlapping), s.description);
      int fp = 0;
      for (PlaceMethod m : {PlaceMethod::SlideGraph, PlaceMethod::SlideMatch}) {
        const MethodFigures f = runScenario(s, m, config, repeats);
        report(rep, s, m, f, repeats);
        fp += f.false_positives + f.wrong;
        if (s.name == "forest" && m == PlaceMethod::SlideGraph) {
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
        for (PlaceMethod m : {PlaceMethod::SlideGraph, PlaceMethod::SlideMatch}) {
          const Cycle c = realCycle(data, set, m, config);
          const std::string prefix = s.name + "." + methodName(m) + ".cycle_";
          const double nan = std::numeric_limits<double>::quiet_NaN();
          rep.add(prefix + "trans_m", c.ok ? c.trans_m : nan, "m").note =
              c.ok ? "|T01 T12 T20| between the three robots' real maps" : "no cycle: " + c.why;
          rep.add(prefix + "yaw_deg", c.ok ? c.yaw_deg : nan, "deg").note = c.ok ? "" : "no cycle";
        }
      }
    }
    if (wanted("indoor_aliased")) {
      for (PlaceMethod m : {PlaceMethod::SlideGraph, PlaceMethod::SlideMatch}) {
        AliasFigures a;
        for (unsigned w = 0; w < 5; ++w) {  // five worlds, 30 re-mappings each
          const AliasFigures one = aliasedRooms(seed + w, m, config, ConsensusParams{}, 30);
          a.attempts += one.attempts, a.raw_found += one.raw_found, a.raw_wrong += one.raw_wrong;
          a.published += one.published, a.published_wrong += one.published_wrong;
        }
        const std::string prefix = std::string("indoor_aliased.") + methodName(m) + ".";
        rep.add(prefix + "raw_wrong_fraction", a.raw_found ? double(a.raw_wrong) / a.raw_found : 0, "", true).note =
            std::to_string(a.raw_wrong) + " wrong of " + std::to_string(a.raw_found) + " found in " +
            std::to_string(a.attempts) + " attempts (5 worlds of two identical rooms)";
        rep.add(prefix + "published_wrong_fraction", a.published ? double(a.published_wrong) / a.published : 0, "", true)
            .note = std::to_string(a.published_wrong) + " wrong of " + std::to_string(a.published) +
                    " published by the consensus filter";
      }
    }
    rep.printTable(std::cout);
    if (!json.empty()) rep.writeJson(json);
    return 0;
  });
}
