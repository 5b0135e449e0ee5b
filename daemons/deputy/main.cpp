// slide-deputy: a procman-compatible deputy. Listens on PM_ORDERS, starts, stops and respawns
// the commands a sheriff assigns to its id, and reports them on PM_INFO and PM_OUTPUT.
#include <limits.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

#include "app/app.h"
#include "deputy_node.h"

namespace {

std::string hostName() {
  char buf[HOST_NAME_MAX + 1] = {};
  gethostname(buf, HOST_NAME_MAX);
  return buf;
}

// Commands find the project's executables when they sit next to the deputy, as with procman.
void prependOwnDirToPath() {
  char exe[PATH_MAX] = {};
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof(exe) - 1);
  if (n <= 0) return;
  std::string dir(exe, exe + n);
  dir = dir.substr(0, dir.rfind('/'));
  const char* path = std::getenv("PATH");
  setenv("PATH", (dir + ":" + (path ? path : "/usr/bin:/bin")).c_str(), 1);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"slide-deputy: procman-compatible deputy (PM_ORDERS in; PM_INFO, PM_OUTPUT out)", "slide-deputy"};
  slide::app::CommonOptions common;
  slide::DeputyOptions opts;
  opts.id = hostName();
  opts.lcm_url = "udpm://239.255.76.67:7667?ttl=0";
  app.add_option("-i,--id", opts.id, "Deputy id (sheriff configs name it as deputy/host)")->capture_default_str();
  app.add_option("-u,--lcm-url", opts.lcm_url, "LCM URL of the procman traffic")->capture_default_str();
  app.add_option("--discovery-ms", opts.discovery_ms, "Time to look for a deputy with the same id at start")
      ->check(CLI::Range(0, 60000))->capture_default_str();
  app.add_option("--shutdown-wait", opts.shutdown_wait_s, "Seconds before SIGKILL when the deputy is stopped")
      ->check(CLI::Range(0.0, 600.0))->capture_default_str();
  slide::app::addCommonOptions(app, common);
  return slide::app::runApp(app, common, argc, argv, [&]() {
    if (opts.id.empty()) throw std::runtime_error("--id must not be empty");
    prependOwnDirToPath();
    slide::DeputyNode node(opts);
    return node.run();
  });
}
