#include "report/suite_runs.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/io_error.h"

namespace slide::report {

const char* statusName(SuiteRun::Status s) {
  switch (s) {
    case SuiteRun::Status::Passed: return "ok";
    case SuiteRun::Status::Failed: return "failed";
    case SuiteRun::Status::Missing: return "missing";
    case SuiteRun::Status::NoResults: return "no-results";
  }
  return "?";
}

std::vector<bench::BenchResult> parseSuiteResults(const Json& doc, const std::string& source) {
  const Json* results = member(doc, "results");
  if (!results || !results->is_array()) throw JsonError(source + ": no \"results\" array");
  std::vector<bench::BenchResult> out;
  for (std::size_t i = 0; i < results->size(); ++i) {
    const Json& r = (*results)[i];
    const std::string where = source + ": results[" + std::to_string(i) + "]";
    const Json* name = member(r, "name");
    const Json* value = member(r, "value");
    if (!name || !name->is_string()) throw JsonError(where + ": \"name\" must be a string");
    if (!value || !(value->is_number() || value->is_null()))
      throw JsonError(where + " (" + name->get<std::string>() + "): \"value\" must be a number or null");
    bench::BenchResult b;
    b.name = name->get<std::string>();
    b.value = value->is_null() ? std::nan("") : value->get<double>();
    if (const Json* u = member(r, "unit"); u && u->is_string()) b.unit = u->get<std::string>();
    if (const Json* t = member(r, "target"); t && t->is_number()) b.target = t->get<double>();
    if (const Json* p = member(r, "paper"); p && p->is_number()) b.paper = p->get<double>();
    if (const Json* n = member(r, "note"); n && n->is_string()) b.note = n->get<std::string>();
    if (const Json* better = member(r, "better"); better && better->is_string()) {
      if (better->get<std::string>() != "lower" && better->get<std::string>() != "higher")
        throw JsonError(where + " (" + b.name + "): \"better\" must be \"lower\" or \"higher\"");
      b.lower_is_better = better->get<std::string>() == "lower";
    }
    out.push_back(b);
  }
  return out;
}

std::vector<SuiteRun> readSuiteRuns(const std::string& manifest_path) {
  std::ifstream in(manifest_path);
  if (!in) throw io::IoError(manifest_path, "cannot open manifest");
  std::vector<SuiteRun> runs;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, '\t')) f.push_back(cell);
    if (f.size() < 3)
      throw io::IoError(manifest_path, "line " + std::to_string(n) + ": expected suite, exit code, wall ms");
    SuiteRun r;
    r.suite = f[0];
    if (f.size() > 3) r.json_path = f[3];
    if (f.size() > 4) r.log_path = f[4];
    try {
      r.wall_s = std::stod(f[2]) / 1000.0;
    } catch (const std::exception&) {
      throw io::IoError(manifest_path, "line " + std::to_string(n) + ": wall time '" + f[2] + "' is not a number");
    }
    if (f[1] == "missing") {
      r.status = SuiteRun::Status::Missing;
      r.exit_code = -1;
      r.problem = "no executable slide-bench-" + r.suite + " (not built, or the suite does not exist yet)";
      runs.push_back(r);
      continue;
    }
    try {
      r.exit_code = std::stoi(f[1]);
    } catch (const std::exception&) {
      throw io::IoError(manifest_path, "line " + std::to_string(n) + ": exit code '" + f[1] + "' is not a number");
    }
    if (r.exit_code != 0) {
      r.status = SuiteRun::Status::Failed;
      r.problem = r.exit_code == 124 ? "timed out (exit code 124)" : "exit code " + std::to_string(r.exit_code);
    }
    // Figures are read even from a failed suite: whatever it wrote is still worth seeing.
    if (r.json_path.empty() || !std::filesystem::exists(r.json_path)) {
      if (r.status == SuiteRun::Status::Passed) {
        r.status = SuiteRun::Status::NoResults;
        r.problem = "wrote no JSON file";
      }
    } else {
      try {
        r.results = parseSuiteResults(readJsonFile(r.json_path), r.json_path);
      } catch (const JsonError& e) {
        if (r.status == SuiteRun::Status::Passed) r.status = SuiteRun::Status::NoResults;
        r.problem += std::string(r.problem.empty() ? "" : "; ") + "bad JSON: " + e.what();
      }
    }
    runs.push_back(r);
  }
  return runs;
}

namespace {
Json resultJson(const bench::BenchResult& r) {
  Json j;
  j["name"] = r.name;
  j["value"] = r.value;
  j["unit"] = r.unit;
  if (r.target) j["target"] = *r.target;
  if (r.paper) j["paper"] = *r.paper;
  j["better"] = r.lower_is_better ? "lower" : "higher";
  if (r.target) j["pass"] = bench::BenchReport::meetsTarget(r);
  if (!r.note.empty()) j["note"] = r.note;
  return j;
}

std::string num(double v) {
  if (!std::isfinite(v)) return "n/a";
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

std::string opt(const std::optional<double>& v) { return v ? num(*v) : "-"; }

std::string cell(std::string s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += "\\|";
    else if (c == '\n') out += ' ';
    else out += c;
  }
  return out;
}

struct Totals {
  int passed = 0, failed = 0, missing = 0, no_results = 0;
  std::size_t figures = 0, targets = 0, met = 0;
};

Totals totals(const std::vector<SuiteRun>& runs) {
  Totals t;
  for (const auto& r : runs) {
    t.passed += r.status == SuiteRun::Status::Passed;
    t.failed += r.status == SuiteRun::Status::Failed;
    t.missing += r.status == SuiteRun::Status::Missing;
    t.no_results += r.status == SuiteRun::Status::NoResults;
    t.figures += r.results.size();
    for (const auto& b : r.results) {
      t.targets += b.target.has_value();
      t.met += bench::BenchReport::meetsTarget(b);
    }
  }
  return t;
}
}  // namespace

Json combinedJson(const std::vector<SuiteRun>& runs, const BenchSummaryInfo& info) {
  Json doc;
  doc["started_utc"] = info.started_utc;
  doc["host"] = info.host;
  doc["command"] = info.command;
  doc["total_wall_s"] = info.total_wall_s;
  Json suites = Json::array();
  for (const auto& r : runs) {
    Json s;
    s["suite"] = r.suite;
    s["status"] = statusName(r.status);
    s["exit_code"] = r.exit_code;
    s["wall_s"] = r.wall_s;
    if (!r.problem.empty()) s["problem"] = r.problem;
    if (!r.log_path.empty()) s["log"] = r.log_path;
    Json res = Json::array();
    for (const auto& b : r.results) res.push_back(resultJson(b));
    s["results"] = res;
    suites.push_back(s);
  }
  doc["suites"] = suites;
  const Totals t = totals(runs);
  Json tj;
  tj["suites"] = runs.size();
  tj["ok"] = t.passed;
  tj["failed"] = t.failed;
  tj["missing"] = t.missing;
  tj["no_results"] = t.no_results;
  tj["figures"] = t.figures;
  tj["targets"] = t.targets;
  tj["targets_met"] = t.met;
  doc["totals"] = tj;
  return doc;
}

std::string markdownReport(const std::vector<SuiteRun>& runs, const BenchSummaryInfo& info) {
  const Totals t = totals(runs);
  std::ostringstream md;
  md << "# Benchmark report\n\n";
  md << "- started: " << info.started_utc << (info.host.empty() ? "" : " on " + info.host) << "\n";
  if (!info.command.empty()) md << "- command: `" << info.command << "`\n";
  md << "- total wall time: " << num(info.total_wall_s) << " s\n";
  md << "- suites: " << runs.size() << " (" << t.passed << " ok, " << t.failed << " failed, " << t.missing << " missing, "
     << t.no_results << " without results)\n";
  md << "- figures: " << t.figures << ", with a target: " << t.targets << ", targets met: " << t.met << "\n\n";
  md << "| suite | status | exit code | wall time [s] | figures | targets met |\n|---|---|---|---|---|---|\n";
  for (const auto& r : runs) {
    std::size_t targets = 0, met = 0;
    for (const auto& b : r.results) {
      targets += b.target.has_value();
      met += bench::BenchReport::meetsTarget(b);
    }
    md << "| " << cell(r.suite) << " | " << statusName(r.status) << " | "
       << (r.status == SuiteRun::Status::Missing ? "-" : std::to_string(r.exit_code)) << " | " << num(r.wall_s) << " | "
       << r.results.size() << " | " << met << "/" << targets << " |\n";
  }
  // Figures off target, all in one place.
  std::ostringstream missed;
  for (const auto& r : runs)
    for (const auto& b : r.results)
      if (b.target && !bench::BenchReport::meetsTarget(b))
        missed << "| " << cell(r.suite) << " | " << cell(b.name) << " | " << num(b.value) << " | " << cell(b.unit) << " | "
               << (b.lower_is_better ? "<= " : ">= ") << num(*b.target) << " | " << opt(b.paper) << " |\n";
  if (!missed.str().empty())
    md << "\n## Figures that miss their target\n\n| suite | name | value | unit | target | paper |\n"
       << "|---|---|---|---|---|---|\n"
       << missed.str();
  for (const auto& r : runs) {
    md << "\n## " << cell(r.suite) << "\n\n";
    if (!r.problem.empty()) md << "**" << statusName(r.status) << "**: " << cell(r.problem) << "\n\n";
    if (!r.log_path.empty()) md << "Log: `" << r.log_path << "`\n\n";
    if (r.results.empty()) {
      md << "No figures.\n";
      continue;
    }
    md << "| name | value | unit | target | paper | pass | note |\n|---|---|---|---|---|---|---|\n";
    for (const auto& b : r.results) {
      const std::string pass = !b.target ? "-" : bench::BenchReport::meetsTarget(b) ? "pass" : "**FAIL**";
      md << "| " << cell(b.name) << " | " << num(b.value) << " | " << cell(b.unit) << " | "
         << (b.target ? (b.lower_is_better ? "<= " : ">= ") + num(*b.target) : "-") << " | " << opt(b.paper) << " | "
         << pass << " | " << cell(b.note) << " |\n";
    }
  }
  return md.str();
}

}  // namespace slide::report
