// slide-benchmark-report: merges the suites' JSON files of one `./slide bench` run (listed in
// the runner's manifest) into one JSON file and a Markdown report, and prints a summary.
#include <spdlog/spdlog.h>

#include <fstream>
#include <iostream>

#include "app/app.h"
#include "report/suite_runs.h"

using namespace slide;

int main(int argc, char** argv) {
  CLI::App app{"slide-benchmark-report: merge benchmark suite results into one JSON file and a Markdown report"};
  app::CommonOptions common;
  app::addCommonOptions(app, common);
  std::string manifest, json_out, md_out;
  report::BenchSummaryInfo info;
  app.add_option("--manifest", manifest, "Runner manifest: suite, exit code|missing, wall ms, json, log (tab-separated)")
      ->required();
  app.add_option("--json", json_out, "Merged JSON output")->required();
  app.add_option("--markdown", md_out, "Markdown report output")->required();
  app.add_option("--total-wall-s", info.total_wall_s, "Wall time of the whole run, seconds");
  app.add_option("--started", info.started_utc, "Start time (UTC, ISO 8601)");
  app.add_option("--host", info.host, "Host name");
  app.add_option("--command", info.command, "The command that was run");
  return app::runApp(app, common, argc, argv, [&] {
    const std::vector<report::SuiteRun> runs = report::readSuiteRuns(manifest);
    report::writeJsonFile(json_out, report::combinedJson(runs, info));
    std::ofstream md(md_out);
    if (!md) throw std::runtime_error(md_out + ": cannot write Markdown report");
    md << report::markdownReport(runs, info);
    if (!md) throw std::runtime_error(md_out + ": write failed");
    int bad = 0;
    std::cout << "\nbenchmark summary (" << info.total_wall_s << " s)\n";
    for (const auto& r : runs) {
      std::size_t targets = 0, met = 0;
      for (const auto& b : r.results) {
        targets += b.target.has_value();
        met += bench::BenchReport::meetsTarget(b);
      }
      std::printf("  %-10s %-10s %7.1f s  %3zu figures, targets met %zu/%zu%s%s\n", r.suite.c_str(),
                  report::statusName(r.status), r.wall_s, r.results.size(), met, targets,
                  r.problem.empty() ? "" : "  -- ", r.problem.c_str());
      bad += r.status != report::SuiteRun::Status::Passed;
    }
    std::cout << "wrote " << json_out << " and " << md_out << "\n";
    return bad ? 1 : 0;
  });
}
