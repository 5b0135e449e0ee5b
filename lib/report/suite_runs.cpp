#include "report/suite_runs.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/io_error.h"

namespace slide {

const char* statusName(SuiteRun::Status s) {
  switch (s) {
    case SuiteRun::Status::Passed: return "ok";
    case SuiteRun::Status::Failed: return "failed";
    case SuiteRun::Status::Missing: return "missing";
    case SuiteRun::Status::NoResults: return "no-results";
  }
  return "?";
}

std::vector<BenchResult> parseSuiteResults(const Json& doc, const std::string& source) {
  const Json* results = doc.find("results");
  if (!results || !results->isArray()) throw JsonError(source + ": no \"results\" array");
  std::vector<BenchResult> out;
  for (std::size_t i = 0; i < results->asArray().size(); ++i) {
    const Json& r = results->asArray()[i];
    const std::string where = source + ": results[" + std::to_string(i) + "]";
    const Json* name = r.find("name");
    const Json* value = r.find("value");
    if (!name || !name->isString()) throw JsonError(where + ": \"name\" must be a string");
    if (!value || !(value->isNumber() || value->isNull()))
      throw JsonError(where + " (" + name->asString() + "): \"value\" must be a number or null");
    BenchResult b;
    b.name = name->asString();
    b.value = value->isNull() ? std::nan("") : value->asNumber();
    if (const Json* u = r.find("unit"); u && u->isString()) b.unit = u->asString();
    if (const Json* t = r.find("target"); t && t->isNumber()) b.target = t->asNumber();
    if (const Json* p = r.find("paper"); p && p->isNumber()) b.paper = p->asNumber();
    if (const Json* n = r.find("note"); n && n->isString()) b.note = n->asString();
    if (const Json* better = r.find("better"); better && better->isString()) {
      if (better->asString() != "lower" && better->asString() != "higher")
        throw JsonError(where + " (" + b.name + "): \"better\" must be \"lower\" or \"higher\"");
      b.lower_is_better = better->asString() == "lower";
    }
    out.push_back(b);
  }
  return out;
}

std::vector<SuiteRun> readSuiteRuns(const std::string& manifest_path) {
  std::ifstream in(manifest_path);
  if (!in) throw IoError(manifest_path, "cannot open manifest");
  std::vector<SuiteRun> runs;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, '\t')) f.push_back(cell);
    if (f.size() < 3) throw IoError(manifest_path, "line " + std::to_string(n) + ": expected suite, exit code, wall ms");
    SuiteRun r;
    r.suite = f[0];
    if (f.size() > 3) r.json_path = f[3];
    if (f.size() > 4) r.log_path = f[4];
    try {
      r.wall_s = std::stod(f[2]) / 1000.0;
    } catch (const std::exception&) {
      throw IoError(manifest_path, "line " + std::to_string(n) + ": wall time '" + f[2] + "' is not a number");
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
      throw IoError(manifest_path, "line " + std::to_string(n) + ": exit code '" + f[1] + "' is not a number");
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
Json resultJson(const BenchResult& r) {
  Json j;
  j.set("name", r.name);
  j.set("value", r.value);
  j.set("unit", r.unit);
  if (r.target) j.set("target", *r.target);
  if (r.paper) j.set("paper", *r.paper);
  j.set("better", r.lower_is_better ? "lower" : "higher");
  if (r.target) j.set("pass", BenchReport::meetsTarget(r));
  if (!r.note.empty()) j.set("note", r.note);
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
      t.met += BenchReport::meetsTarget(b);
    }
  }
  return t;
}
}  // namespace

Json combinedJson(const std::vector<SuiteRun>& runs, const BenchSummaryInfo& info) {
  Json doc;
  doc.set("started_utc", info.started_utc);
  doc.set("host", info.host);
  doc.set("command", info.command);
  doc.set("total_wall_s", info.total_wall_s);
  Json suites = Json::array();
  for (const auto& r : runs) {
    Json s;
    s.set("suite", r.suite);
    s.set("status", statusName(r.status));
    s.set("exit_code", r.exit_code);
    s.set("wall_s", r.wall_s);
    if (!r.problem.empty()) s.set("problem", r.problem);
    if (!r.log_path.empty()) s.set("log", r.log_path);
    Json res = Json::array();
    for (const auto& b : r.results) res.push(resultJson(b));
    s.set("results", res);
    suites.push(s);
  }
  doc.set("suites", suites);
  const Totals t = totals(runs);
  Json tj;
  tj.set("suites", runs.size());
  tj.set("ok", t.passed);
  tj.set("failed", t.failed);
  tj.set("missing", t.missing);
  tj.set("no_results", t.no_results);
  tj.set("figures", t.figures);
  tj.set("targets", t.targets);
  tj.set("targets_met", t.met);
  doc.set("totals", tj);
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
      met += BenchReport::meetsTarget(b);
    }
    md << "| " << cell(r.suite) << " | " << statusName(r.status) << " | "
       << (r.status == SuiteRun::Status::Missing ? "-" : std::to_string(r.exit_code)) << " | " << num(r.wall_s) << " | "
       << r.results.size() << " | " << met << "/" << targets << " |\n";
  }
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
      const std::string pass = !b.target ? "-" : BenchReport::meetsTarget(b) ? "pass" : "**FAIL**";
      md << "| " << cell(b.name) << " | " << num(b.value) << " | " << cell(b.unit) << " | "
         << (b.target ? (b.lower_is_better ? "<= " : ">= ") + num(*b.target) : "-") << " | " << opt(b.paper) << " | "
         << pass << " | " << cell(b.note) << " |\n";
    }
  }
  return md.str();
}

}  // namespace slide
