#pragma once
// Benchmark figures in the project's convention (BENCHMARKS.md): a table on stdout and,
// on request, {"suite": ..., "results": [{name, value, unit, target?, paper?, better}]}.
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace slide::bench {

struct BenchResult {
  std::string name;   // e.g. "forest.update_ms.median"
  double value = 0;
  std::string unit;   // "ms", "m", "deg", "bytes", "" for ratios and counts
  std::optional<double> target;
  std::optional<double> paper;
  bool lower_is_better = true;
  std::string note;   // free text shown in the table (e.g. "median of 20 runs")
};

class BenchReport {
 public:
  explicit BenchReport(std::string suite) : suite_(std::move(suite)) {}

  BenchResult& add(BenchResult r);
  // Shorthand: add(name, value, unit, lower_is_better, target, paper).
  BenchResult& add(const std::string& name, double value, const std::string& unit, bool lower_is_better = true,
                   std::optional<double> target = std::nullopt, std::optional<double> paper = std::nullopt);

  const std::string& suite() const { return suite_; }
  const std::vector<BenchResult>& results() const { return results_; }
  // A result meets its target when it has one and is on the right side of it.
  static bool meetsTarget(const BenchResult& r);

  void printTable(std::ostream& out) const;
  std::string toJson() const;
  // Writes toJson() to `path`; throws std::runtime_error naming the path on failure.
  void writeJson(const std::string& path) const;

 private:
  std::string suite_;
  std::vector<BenchResult> results_;
};

}  // namespace slide::bench
