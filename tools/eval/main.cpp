// slide-eval: standard metrics on any run's output or on TUM/KITTI files from elsewhere —
// ATE and RPE of trajectories, object-map precision/recall/F1 and landmark RMSE, error of an
// inter-robot transform, bandwidth per landmark and per metre, per-stage runtime statistics.
#include <spdlog/spdlog.h>

#include <cstdio>

#include "app/app.h"
#include "commands.h"

using namespace slide;

int main(int argc, char** argv) {
  CLI::App app{"slide-eval: trajectory, map, transform, bandwidth and runtime metrics"};
  app::CommonOptions common;
  app::addCommonOptions(app, common);
  std::string json_path;
  app.add_option("--json", json_path, "Also write the results as JSON to this file");
  app.require_subcommand(1);
  app.fallthrough();  // --json and --log-level also after the subcommand
  std::vector<std::pair<CLI::App*, EvalCommand>> commands;
  auto add = [&](const char* name, const char* help, EvalCommand (*adder)(CLI::App*)) {
    CLI::App* sub = app.add_subcommand(name, help);
    commands.emplace_back(sub, adder(sub));
  };
  add("ate", "Absolute trajectory error: EST REF [--align se3|sim3|yaw|none]", addAteCommand);
  add("rpe", "Relative pose error: EST REF [--delta N --unit frames|m]", addRpeCommand);
  add("objects", "Object map precision, recall, F1 per class and landmark RMSE: EST GT [--threshold M]",
      addObjectsCommand);
  add("transform", "Error of an estimated transform against the true one (translation, yaw, rotation)",
      addTransformCommand);
  add("bandwidth", "Bytes per landmark and per metre travelled", addBandwidthCommand);
  add("timing", "Per-stage runtime statistics (median, 99th percentile) from 'stage value' lines", addTimingCommand);
  return app::runApp(app, common, argc, argv, [&] {
    for (auto& [sub, cmd] : commands) {
      if (!sub->parsed()) continue;
      const report::Json result = cmd();
      if (!json_path.empty()) {
        report::writeJsonFile(json_path, result);
        spdlog::info("wrote {}", json_path);
      }
      return 0;
    }
    return 1;
  });
}
