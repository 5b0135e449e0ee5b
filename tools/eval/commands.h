#pragma once
// The subcommands of slide-eval: each registers its options on the CLI and, when chosen,
// prints readable results and returns them as JSON (written with --json).
#include <CLI/CLI.hpp>
#include <functional>
#include <string>

#include "eval/error_stats.h"
#include "report/json.h"

namespace slide {

using EvalCommand = std::function<report::Json()>;

// Each adds its options to the subcommand `cmd` and returns what runs when it is chosen.
EvalCommand addAteCommand(CLI::App* cmd);
EvalCommand addRpeCommand(CLI::App* cmd);
EvalCommand addObjectsCommand(CLI::App* cmd);
EvalCommand addTransformCommand(CLI::App* cmd);
EvalCommand addBandwidthCommand(CLI::App* cmd);
EvalCommand addTimingCommand(CLI::App* cmd);

// {"rmse": .., "mean": .., "median": .., "std": .., "min": .., "max": .., "count": ..}
report::Json statsJson(const eval::ErrorStats& s);
// "rmse 1.234  mean ...  (n = 42)" with a unit after each number.
std::string statsLine(const eval::ErrorStats& s, const std::string& unit);

}  // namespace slide
