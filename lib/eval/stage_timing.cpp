#include "eval/stage_timing.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

#include "bench/stats.h"
#include "io/io_error.h"
#include "io/numbers.h"

namespace slide::eval {

std::vector<StageTiming> stageTimings(const std::map<std::string, std::vector<double>>& samples) {
  std::vector<StageTiming> out;
  for (const auto& [stage, v] : samples) {
    if (v.empty()) continue;
    StageTiming t;
    t.stage = stage;
    t.count = v.size();
    t.median = bench::median(v);
    t.p99 = bench::quantile(v, 0.99);
    t.mean = bench::mean(v);
    t.max = *std::max_element(v.begin(), v.end());
    out.push_back(t);
  }
  return out;
}

std::map<std::string, std::vector<double>> readStageSamples(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw io::IoError(path, "cannot open file");
  std::map<std::string, std::vector<double>> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream s(line);
    std::string a, b, extra;
    s >> a >> b >> extra;
    const std::string stage = b.empty() ? "all" : a;
    const std::string num = b.empty() ? a : b;
    const std::optional<double> v = io::parseNumber(num);
    if (!v || !std::isfinite(*v) || !extra.empty())
      throw io::IoError(path, "line " + std::to_string(n) + ": expected 'stage value' or 'value', got '" + line + "'");
    out[stage].push_back(*v);
  }
  return out;
}

}  // namespace slide::eval
