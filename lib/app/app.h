#pragma once
// Shared start-up for every executable: CLI11 options common to all, spdlog set-up, and a
// main() wrapper that turns exceptions into one clear error line and exit code 1.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace slide::app {

struct CommonOptions {
  std::string log_level = "info";
};

// Adds --log-level (trace|debug|info|warn|error|off) to `app`.
void addCommonOptions(CLI::App& app, CommonOptions& opts);

// Applies the logging options: pattern "[time] [name] [level] message" on stderr.
void setupLogging(const std::string& program, const CommonOptions& opts);

// Where a daemon keeps state that must survive a reboot (journals, counters): /var/lib/slide
// for root, else $XDG_STATE_HOME/slide, else $HOME/.local/state/slide. Never under /tmp.
std::string persistentStateDir();

// Parses argv into `app`, sets up logging, then runs `body`; returns the process exit code.
// CLI errors print usage; exceptions from body are logged as errors and give exit code 1.
int runApp(CLI::App& app, CommonOptions& opts, int argc, char** argv, const std::function<int()>& body);

}  // namespace slide::app
