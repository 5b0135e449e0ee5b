#pragma once
// slide-sheriff's LCM side: hears PM_INFO (and PM_OUTPUT), sends PM_ORDERS for every deputy
// of the config, and drives a ScriptRunner.
#include <lcm/lcm-cpp.hpp>

#include <memory>
#include <string>

#include "procman/pmd_config.h"
#include "procman/script_runner.h"
#include "procman/sheriff_model.h"
#include "procman_lcm/deputy_info_t.hpp"
#include "procman_lcm/output_t.hpp"

namespace slide {

struct SheriffOptions {
  std::string lcm_url;
  std::string id;
  std::string script;            // empty: observe only
  double wait_timeout_s = 30;    // per wait, and for the final check
  double deputy_timeout_s = 5;   // to hear from every deputy before the script starts
  double listen_s = 2;           // observer mode: how long to listen
  double linger_s = 0;           // keep sending orders this long after the script
  bool show_output = false;
};

class SheriffNode {
 public:
  SheriffNode(const procman::PmdConfig& cfg, const SheriffOptions& opts);
  // Runs the script (or observes); prints the status table; returns the exit code.
  int run();

  void onInfo(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::deputy_info_t* m);
  void onOutput(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::output_t* m);

 private:
  void spin(double seconds);  // handle LCM for a while
  void sendOrders(int64_t now);

  const procman::PmdConfig& cfg_;
  SheriffOptions opts_;
  lcm::LCM lcm_;
  procman::SheriffModel model_;
};

}  // namespace slide
