#pragma once
// The place benchmark's scenarios as lists of map pairs with ground truth, and the figures
// of running a method over them.
#include <map>

#include "place/place_config.h"
#include "worlds.h"

namespace slide::bench {

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
MethodFigures runScenario(const Scenario& s, PlaceMethod method, const PlaceConfig& config, int repeats);

// Real robot maps: T01 * T12 * T20 for the three robots of `set`; false when a link is missing.
struct Cycle {
  bool ok = false;
  double trans_m = 0, yaw_deg = 0;
  std::string why;
};
Cycle realCycle(const std::string& data_dir, const std::string& set, PlaceMethod method, const PlaceConfig& config);

}  // namespace slide::bench
