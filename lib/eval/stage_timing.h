#pragma once
// Per-stage runtime statistics (median, 99th percentile) from timing samples.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace slide::eval {

struct StageTiming {
  std::string stage;
  std::size_t count = 0;
  double median = 0, p99 = 0, mean = 0, max = 0;  // in the samples' unit (ms by convention)
};

// One entry per stage, in name order; quantiles interpolate linearly (lib/bench/stats.h).
std::vector<StageTiming> stageTimings(const std::map<std::string, std::vector<double>>& samples);

// Reads timing samples: one "stage value" pair per line ('#' comments, blank lines allowed);
// a line with a single number counts for stage "all". Throws IoError naming file and line.
std::map<std::string, std::vector<double>> readStageSamples(const std::string& path);

}  // namespace slide::eval
