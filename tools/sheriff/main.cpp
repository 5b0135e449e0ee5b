// slide-sheriff: a headless procman sheriff. Reads a .pmd config, runs one of its scripts by
// sending PM_ORDERS to the deputies, prints the status table, and exits non-zero when a
// command does not reach the state the script asked for.
#include <unistd.h>

#include <limits.h>

#include "app/app.h"
#include "procman/pmd_config.h"
#include "sheriff_node.h"

int main(int argc, char** argv) {
  CLI::App app{"slide-sheriff: run a procman (.pmd) script headless, or print the team's status", "slide-sheriff"};
  slide::app::CommonOptions common;
  slide::SheriffOptions opts;
  std::string config;
  char host[HOST_NAME_MAX + 1] = {};
  gethostname(host, HOST_NAME_MAX);
  opts.id = std::string("slide-sheriff-") + host + "-" + std::to_string(getpid());
  opts.lcm_url = "udpm://239.255.76.67:7667?ttl=0";
  app.add_option("-c,--config", config, "procman config (.pmd)")->required()->check(CLI::ExistingFile);
  app.add_option("-s,--script", opts.script, "Script to run (none: only print the status table)");
  app.add_option("-u,--lcm-url", opts.lcm_url, "LCM URL of the procman traffic")->capture_default_str();
  app.add_option("--id", opts.id, "Sheriff id sent in orders");
  app.add_option("--wait-timeout", opts.wait_timeout_s, "Seconds a wait (and the final check) may take")
      ->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--deputy-timeout", opts.deputy_timeout_s, "Seconds to hear from every deputy before the script")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_option("--listen", opts.listen_s, "Without --script: seconds to listen before printing")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_option("--linger", opts.linger_s, "Keep sending orders this many seconds after the script")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_flag("--show-output", opts.show_output, "Print the commands' output (PM_OUTPUT)");
  slide::app::addCommonOptions(app, common);
  return slide::app::runApp(app, common, argc, argv, [&]() {
    const slide::procman::PmdConfig cfg = slide::procman::loadPmd(config);
    slide::SheriffNode node(cfg, opts);
    return node.run();
  });
}
