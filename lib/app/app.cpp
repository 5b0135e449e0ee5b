#include "app/app.h"

#include <unistd.h>

#include <cstdlib>
#include <stdexcept>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace slide::app {

void addCommonOptions(CLI::App& app, CommonOptions& opts) {
  app.add_option("--log-level", opts.log_level, "Log level")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}))
      ->capture_default_str();
}

void setupLogging(const std::string& program, const CommonOptions& opts) {
  auto logger = spdlog::stderr_color_mt(program);
  logger->set_pattern("[%H:%M:%S.%e] [%n] [%^%l%$] %v");
  logger->set_level(spdlog::level::from_str(opts.log_level));
  spdlog::set_default_logger(logger);
}

int runApp(CLI::App& app, CommonOptions& opts, int argc, char** argv, const std::function<int()>& body) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  setupLogging(app.get_name(), opts);
  try {
    return body();
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}

std::string persistentStateDir() {
  if (geteuid() == 0) return "/var/lib/slide";
  if (const char* x = std::getenv("XDG_STATE_HOME"); x && x[0] == '/') return std::string(x) + "/slide";
  const char* home = std::getenv("HOME");
  if (!home || home[0] != '/') throw std::runtime_error("no state folder: set HOME or XDG_STATE_HOME, or give one explicitly");
  return std::string(home) + "/.local/state/slide";
}

}  // namespace slide::app
