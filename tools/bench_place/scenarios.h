#pragma once
// The place benchmark's scenarios as lists of map pairs with ground truth, and the figures
// of running a method over them.
#include <map>

#include "place/consensus_filter.h"
#include "place/place_config.h"
#include "worlds.h"

namespace slide::bench_place {

struct PairCase {
  RobotMap a, b;
  bool overlapping = true;  // false: a pair that must give no transform
};

struct Scenario {
  std::string name;  // indoor, urban, forest, kitti05, kitti07, parking_real, indoor_real
  std::vector<PairCase> pairs;
  std::string description;
};

Scenario indoorScenario(unsigned seed);
Scenario urbanScenario(unsigned seed);
Scenario forestScenario(unsigned seed, int overlapping, int disjoint);
Scenario kittiScenario(const std::string& data_dir, const std::string& seq, unsigned seed);
// Each real map against copies moved by random transforms (noise, dropped objects).
Scenario realScenario(const std::string& data_dir, const std::string& set, unsigned seed);

struct MethodFigures {
  std::vector<double> trans_err, yaw_err, ms, cpu_ms;  // errors of correct results; times of every run
  std::map<std::string, std::vector<double>> stage_cpu_ms;
  int overlapping = 0, correct = 0, wrong = 0, missed = 0, disjoint = 0, false_positives = 0;
  std::size_t peak_bytes = 0, max_associations = 0;
};

// Runs `method` on every pair (`repeats` timed runs each; the first is scored). A result is
// correct within 1 m and 2 degrees of the truth; otherwise (or on a disjoint pair) it is wrong.
MethodFigures runScenario(const Scenario& s, place::PlaceMethod method, const place::PlaceConfig& config, int repeats);

// CLIPPER alone on a large association set: for every landmark of B its true partner in A
// (when A has it) plus `outliers_per_landmark` random landmarks of A.
struct ClipperStress {
  std::size_t associations = 0, true_associations = 0, selected = 0, selected_true = 0, edges = 0, peak_bytes = 0;
  double ms = 0;
};
ClipperStress clipperStress(const PairCase& c, int outliers_per_landmark, const place::ClipperParams& params,
                            unsigned seed);

// Two identical rooms side by side (perfect alias) plus a few objects only in the second; A
// maps both, B re-maps the second room `attempts` times (new noise and missed objects each
// time). Raw results and the consensus filter's held transform are scored against the truth.
struct AliasFigures {
  int attempts = 0, raw_found = 0, raw_wrong = 0, published = 0, published_wrong = 0;
};
AliasFigures aliasedRooms(unsigned seed, place::PlaceMethod method, const place::PlaceConfig& config,
                          const place::ConsensusParams& consensus, int attempts);

// Real robot maps: T01 * T12 * T20 for the three robots of `set`; false when a link is missing.
struct Cycle {
  bool ok = false;
  double trans_m = 0, yaw_deg = 0;
  std::string why;
};
Cycle realCycle(const std::string& data_dir, const std::string& set, place::PlaceMethod method,
                const place::PlaceConfig& config);

}  // namespace slide::bench_place
