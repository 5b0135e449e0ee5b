#pragma once
// Conversions between the procman core types (lib/procman) and procman_lcm messages, shared
// by slide-deputy and slide-sheriff.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "procman/command.h"
#include "procman/proc_stats.h"
#include "procman_lcm/cmd_t.hpp"
#include "procman_lcm/deputy_info_t.hpp"
#include "procman_lcm/orders_t.hpp"
#include "procman_lcm/output_t.hpp"

namespace slide::msg {

procman_lcm::cmd_t toLcm(const procman::CommandSpec& s);
procman::CommandSpec fromLcm(const procman_lcm::cmd_t& m);

procman_lcm::orders_t makeOrders(const std::string& deputy_id, const std::string& sheriff_id, int64_t utime,
                                 const std::vector<procman::DesiredCommand>& cmds);
std::vector<procman::DesiredCommand> desiredCommands(const procman_lcm::orders_t& m);

procman_lcm::deputy_info_t makeDeputyInfo(const std::string& deputy_id, int64_t utime, float cpu_load,
                                          const procman::MemoryInfo& mem,
                                          const std::vector<procman::CommandReport>& cmds);
std::vector<procman::CommandReport> commandReports(const procman_lcm::deputy_info_t& m);

// One PM_OUTPUT message from (command id, text) pairs; an empty id marks the deputy's own text.
procman_lcm::output_t makeOutput(const std::string& deputy_id, int64_t utime,
                                 const std::vector<std::pair<std::string, std::string>>& batch);

}  // namespace slide::msg
