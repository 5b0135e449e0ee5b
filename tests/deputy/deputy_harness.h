#pragma once
// Runs slide-deputy as a subprocess and talks procman LCM to it, like a sheriff would.
#include <lcm/lcm-cpp.hpp>
#include <sys/types.h>

#include <functional>
#include <string>
#include <vector>

#include "procman/command.h"
#include "procman_lcm/deputy_info_t.hpp"
#include "procman_lcm/output_t.hpp"

namespace slide::test {

constexpr const char* kTestUrl = "udpm://239.255.76.67:7667?ttl=0";

// Starts slide-deputy with the given id; returns its pid.
pid_t startDeputy(const std::string& id);
// Waits up to timeout_s for pid to exit; returns its wait status or -1 on timeout.
int waitExit(pid_t pid, double timeout_s);

class SheriffStub {
 public:
  SheriffStub();
  void onInfo(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::deputy_info_t* m);
  void onOutput(const lcm::ReceiveBuffer*, const std::string&, const procman_lcm::output_t* m);

  // Sends orders now and (re)sends them every 0.5 s while waiting, as a sheriff does.
  void order(const std::string& deputy, const std::vector<procman::DesiredCommand>& cmds, int64_t utime_offset_us = 0);
  // Handles LCM until pred() holds on the latest PM_INFO of the deputy, or timeout_s passes.
  bool waitFor(const std::function<bool(const procman_lcm::deputy_info_t&)>& pred, double timeout_s);
  void spin(double seconds);

  bool have_info = false;
  procman_lcm::deputy_info_t info;
  std::string output;  // all PM_OUTPUT text, "id: text" per entry

 private:
  lcm::LCM lcm_;
  std::string deputy_;
  std::vector<procman::DesiredCommand> orders_;
  int64_t offset_us_ = 0;
  int64_t next_send_us_ = 0;
};

// The status of command id in info, or nullptr.
const procman_lcm::cmd_status_t* findCommand(const procman_lcm::deputy_info_t& info, const std::string& id);

procman::DesiredCommand command(const std::string& id, const std::string& exec, int32_t runid, bool force_quit = false,
                                bool respawn = false);

}  // namespace slide::test
