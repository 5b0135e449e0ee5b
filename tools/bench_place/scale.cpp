#include "scale.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <iostream>
#include <limits>

#include "bench/stats.h"
#include "realistic.h"

namespace slide::bench_place {

namespace {
constexpr double kSharedStretch = 200;  // metres of route both robots drive

struct Sizing {
  double route_length;
  int pairs, disjoint;
};
// Route length for about `objects` objects per map: the world's density over the sensor's swath,
// less the missed, plus the spurious objects (revisits make maps a little smaller).
Sizing sizingFor(int objects, const RouteWorld& w, const simulator::MapErrorParams& e) {
  const double per_metre = 0.1 * 2 * w.range * (1 - e.missed) * (1 + e.spurious);
  const int pairs = objects <= 2000 ? 6 : (objects <= 15000 ? 4 : 2);
  return {std::max(2 * kSharedStretch, objects / per_metre), pairs, objects <= 15000 ? 2 : 1};
}
}  // namespace

void runScale(bench::BenchReport& rep, const place::PlaceConfig& config, unsigned seed, const std::vector<int>& sizes,
              const std::vector<std::string>& conditions) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const RouteWorld base = routeWorld("forest_scale", seed);
  spdlog::info("place scale: {}", base.description);
  std::string table =
      "| objects | condition | method | maps (A x B, median) | recall | wrong | FP | trans m | CPU ms (median / max) | peak MB |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n";
  unsigned k = 0;
  for (int n : sizes)
    for (const std::string& cond : conditions) {
      ++k;
      Condition c;
      c.name = cond;
      c.errors = conditionErrors(cond);
      RouteWorld w = base;
      const Sizing s = sizingFor(n, w, c.errors);
      w.route_length = s.route_length;
      c.overlap = kSharedStretch / s.route_length;
      c.pairs = s.pairs;
      c.disjoint_pairs = s.disjoint;
      const std::vector<MapPair> pairs = makePairs(w, c, seed * 7919 + k);
      spdlog::info("place scale {} {}: routes of {:.0f} m, {} overlapping (200 m shared) + {} disjoint pairs", n, cond,
                   s.route_length, c.pairs, c.disjoint_pairs);
      for (place::PlaceMethod m : {place::PlaceMethod::SlideGraph, place::PlaceMethod::SlideMatch}) {
        const RealisticFigures f = runPairs(pairs, m, config, 2 * w.range);
        const std::string prefix = "place." + std::to_string(n) + "." + cond + "." + place::methodName(m) + ".";
        const bool at10k = n == 10000;
        const std::string maps = fmt::format("maps {:.0f} x {:.0f} objects (median)", bench::median(f.objects_a),
                                             bench::median(f.objects_b));
        rep.add(prefix + "recall", double(f.correct) / f.overlapping, "", false).note =
            fmt::format("{} correct of {} overlapping pairs ({} missed, {} wrong), one 200 m stretch shared, {} condition; {}{}",
                        f.correct, f.overlapping, f.missed, f.wrong, cond, maps,
                        f.missed ? "; missed: " + joined(f.miss_notes) : "");
        rep.add(prefix + "wrong", f.wrong, "", true, 0.0).note =
            f.wrong ? joined(f.wrong_notes)
                    : "found but more than 1 m or 2 deg off the least-squares truth of every place the maps share (runs of "
                      "shared objects along A's route, split at gaps over 30 m; error at the place's centroid)";
        rep.add(prefix + "false_positives", f.false_positives, "", true, 0.0).note =
            fmt::format("transforms on {} pairs in disjoint halves of the world", f.disjoint);
        rep.add(prefix + "trans_err_m", f.trans_err.empty() ? nan : bench::median(f.trans_err), "m").note =
            "median over the correct, against the least-squares truth over the shared objects";
        const std::optional<double> ms_target =
            at10k ? std::optional<double>(m == place::PlaceMethod::SlideGraph ? 100.0 : 5000.0) : std::nullopt;
        rep.add(prefix + "ms.median", bench::median(f.cpu_ms), "ms", true,
                m == place::PlaceMethod::SlideGraph ? ms_target : std::nullopt)
            .note = fmt::format("thread CPU time of one query, median over {} pairs; {}", f.cpu_ms.size(), maps);
        rep.add(prefix + "ms.max", *std::max_element(f.cpu_ms.begin(), f.cpu_ms.end()), "ms", true,
                m == place::PlaceMethod::SlideMatch ? ms_target : std::nullopt)
            .note = "thread CPU time, slowest query";
        for (const auto& [stage, v] : f.stage_cpu_ms)
          rep.add(prefix + "stage_ms." + stage, bench::median(v), "ms").note =
              "thread CPU time of the stage per query, median";
        const double peak = *std::max_element(f.peak_mb.begin(), f.peak_mb.end());
        rep.add(prefix + "peak_mb", peak, "MB").note =
            "largest peak resident memory of a query above the process's before it (VmHWM reset per query)";
        table +=
            fmt::format("| {} | {} | {} | {:.0f} x {:.0f} | {}/{} | {} | {}/{} | {} | {:.0f} / {:.0f} | {:.0f} |\n", n,
                        cond, place::methodName(m), bench::median(f.objects_a), bench::median(f.objects_b), f.correct,
                        f.overlapping, f.wrong, f.false_positives, f.disjoint,
                        f.trans_err.empty() ? "-" : fmt::format("{:.2f}", bench::median(f.trans_err)),
                        bench::median(f.cpu_ms), *std::max_element(f.cpu_ms.begin(), f.cpu_ms.end()), peak);
        spdlog::info("place scale {} {} {}: {}/{} correct, {} wrong, {}/{} FP, CPU median {:.0f} ms", n, cond,
                     place::methodName(m), f.correct, f.overlapping, f.wrong, f.false_positives, f.disjoint,
                     bench::median(f.cpu_ms));
      }
    }
  std::cout << "\nPlace recognition at scale (one query per pair; wrong: > 1 m or > 2 deg from the least-squares truth over "
               "shared objects):\n"
            << table << std::endl;
}

}  // namespace slide::bench_place
