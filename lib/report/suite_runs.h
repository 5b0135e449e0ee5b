#pragma once
// The benchmark runner's record of one `./slide bench` run: which suites ran, how they ended,
// their figures, and the merged JSON and Markdown report written from it.
//
// The runner (tools/commands/bench.sh) writes a manifest, one suite a line, tab-separated:
//   suite  exit_code|missing  wall_ms  json_path  log_path
#include <string>
#include <vector>

#include "bench/report.h"
#include "report/json.h"

namespace slide::report {

struct SuiteRun {
  enum class Status { Passed, Failed, Missing, NoResults };
  std::string suite;
  Status status = Status::Passed;
  int exit_code = 0;
  double wall_s = 0;
  std::string json_path, log_path;
  std::vector<bench::BenchResult> results;
  std::string problem;  // why the suite failed or has no results
};

const char* statusName(SuiteRun::Status s);

// Reads the manifest and each suite's JSON (BENCHMARKS.md convention). A suite whose JSON is
// absent or unreadable is kept, with the problem recorded, never dropped. Throws IoError for
// a missing or malformed manifest (naming file and line).
std::vector<SuiteRun> readSuiteRuns(const std::string& manifest_path);

// Parses one suite's JSON; throws JsonError naming the file and the bad field.
std::vector<bench::BenchResult> parseSuiteResults(const Json& doc, const std::string& source);

struct BenchSummaryInfo {
  double total_wall_s = 0;
  std::string started_utc;  // e.g. "2026-11-22T12:00:00Z"
  std::string host;
  std::string command;
};

// {"started_utc", "host", "command", "total_wall_s", "suites": [{suite, status, exit_code,
//   wall_s, problem?, results: [...]}], "totals": {suites, passed, failed, missing,
//   figures, targets, targets_met}}
Json combinedJson(const std::vector<SuiteRun>& runs, const BenchSummaryInfo& info);

// A Markdown report: a summary table of suites, then per suite a table of figures with value,
// unit, target, paper and pass/fail ("-" without a target).
std::string markdownReport(const std::vector<SuiteRun>& runs, const BenchSummaryInfo& info);

}  // namespace slide::report
