#pragma once
// slide-deputy's event loop: procman's LCM protocol (PM_DISCOVER, PM_ORDERS, PM_INFO,
// PM_OUTPUT) around the process table of lib/procman.
#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "msg/inbox.h"
#include "procman/output_batcher.h"
#include "procman/proc_stats.h"
#include "procman/process_table.h"
#include "procman_lcm/deputy_info_t.hpp"
#include "procman_lcm/discovery_t.hpp"
#include "procman_lcm/orders_t.hpp"

namespace slide {

struct DeputyOptions {
  std::string id;
  std::string lcm_url;
  int discovery_ms = 500;        // listen for a deputy with the same id this long at start
  double shutdown_wait_s = 3.0;  // SIGKILL what is left this long after SIGINT/SIGTERM
};

class DeputyNode {
 public:
  explicit DeputyNode(const DeputyOptions& opts);
  ~DeputyNode();
  // Runs until SIGINT/SIGTERM (0) or a conflicting deputy is found (2).
  int run();

  void onOrders(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::orders_t* m);
  void onDiscover(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::discovery_t* m);
  void onInfo(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::deputy_info_t* m);

 private:
  struct Usage {
    procman::ProcessTimes last;
    float cpu = 0.f;
  };
  bool discovering(int64_t now) const { return now < start_us_ + opts_.discovery_ms * 1000LL; }
  void execute(const std::vector<procman::Action>& actions, int64_t now);
  void reapChildren(int64_t now);
  void readOutput(int fd, int64_t now);
  void closeOutput(int fd, int64_t now);
  void handleSignals(int64_t now);
  void sampleUsage();
  void publishInfo(int64_t now);
  void publishOutput(int64_t now);
  void say(const std::string& command_id, const std::string& text, int64_t now);

  DeputyOptions opts_;
  lcm::LCM lcm_;
  msg::Inbox inbox_{lcm_};  // every PM_* message checked before it is decoded
  int signal_fd_ = -1;
  int64_t start_us_ = 0;
  int64_t nonce_ = 0;
  int exit_code_ = -1;  // >=0 once the loop must end
  bool exiting_ = false;
  int64_t exit_deadline_us_ = 0;
  bool info_dirty_ = false;
  procman::ProcessTable table_;
  procman::OutputBatcher output_;
  std::map<int, std::string> output_fds_;  // pipe fd -> command id
  std::map<int, int> pid_fd_;              // pid -> pipe fd (while open)
  std::map<int, Usage> usage_;             // pid -> CPU sampling
  procman::SystemTimes last_sys_;
  float cpu_load_ = 0.f;
  procman::MemoryInfo mem_;
};

}  // namespace slide
