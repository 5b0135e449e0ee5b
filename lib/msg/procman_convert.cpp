#include "msg/procman_convert.h"

namespace slide::msg {

procman_lcm::cmd_t toLcm(const procman::CommandSpec& s) {
  procman_lcm::cmd_t m;
  m.command_id = s.id;
  m.exec_str = s.exec;
  m.group = s.group;
  m.auto_respawn = s.auto_respawn;
  m.stop_signal = static_cast<int8_t>(s.stop_signal);
  m.stop_time_allowed = static_cast<float>(s.stop_time_allowed);
  return m;
}

procman::CommandSpec fromLcm(const procman_lcm::cmd_t& m) {
  procman::CommandSpec s;
  s.id = m.command_id;
  s.exec = m.exec_str;
  s.group = m.group;
  s.auto_respawn = m.auto_respawn;
  s.stop_signal = m.stop_signal > 0 ? m.stop_signal : SIGINT;  // procman's default for 0
  s.stop_time_allowed = m.stop_time_allowed > 0 ? m.stop_time_allowed : 7.0;
  return s;
}

procman_lcm::orders_t makeOrders(const std::string& deputy_id, const std::string& sheriff_id, int64_t utime,
                                 const std::vector<procman::DesiredCommand>& cmds) {
  procman_lcm::orders_t m;
  m.utime = utime;
  m.deputy_id = deputy_id;
  m.sheriff_id = sheriff_id;
  for (const procman::DesiredCommand& d : cmds) {
    procman_lcm::cmd_desired_t c;
    c.cmd = toLcm(d.spec);
    c.desired_runid = d.desired_runid;
    c.force_quit = d.force_quit;
    m.cmds.push_back(c);
  }
  m.ncmds = static_cast<int32_t>(m.cmds.size());
  return m;
}

std::vector<procman::DesiredCommand> desiredCommands(const procman_lcm::orders_t& m) {
  std::vector<procman::DesiredCommand> out;
  for (const procman_lcm::cmd_desired_t& c : m.cmds) out.push_back({fromLcm(c.cmd), c.desired_runid, c.force_quit});
  return out;
}

procman_lcm::deputy_info_t makeDeputyInfo(const std::string& deputy_id, int64_t utime, float cpu_load,
                                          const procman::MemoryInfo& mem,
                                          const std::vector<procman::CommandReport>& cmds) {
  procman_lcm::deputy_info_t m;
  m.utime = utime;
  m.deputy_id = deputy_id;
  m.cpu_load = cpu_load;
  m.phys_mem_total_bytes = mem.total_bytes;
  m.phys_mem_free_bytes = mem.free_bytes;
  m.swap_total_bytes = mem.swap_total_bytes;
  m.swap_free_bytes = mem.swap_free_bytes;
  for (const procman::CommandReport& r : cmds) {
    procman_lcm::cmd_status_t s;
    s.cmd = toLcm(r.spec);
    s.pid = r.pid;
    s.actual_runid = r.actual_runid;
    s.exit_code = r.exit_code;
    s.cpu_usage = r.cpu_usage;
    s.mem_vsize_bytes = r.mem_vsize_bytes;
    s.mem_rss_bytes = r.mem_rss_bytes;
    m.cmds.push_back(s);
  }
  m.ncmds = static_cast<int32_t>(m.cmds.size());
  return m;
}

std::vector<procman::CommandReport> commandReports(const procman_lcm::deputy_info_t& m) {
  std::vector<procman::CommandReport> out;
  for (const procman_lcm::cmd_status_t& s : m.cmds) {
    procman::CommandReport r;
    r.spec = fromLcm(s.cmd);
    r.pid = s.pid;
    r.actual_runid = s.actual_runid;
    r.exit_code = s.exit_code;
    r.cpu_usage = s.cpu_usage;
    r.mem_vsize_bytes = s.mem_vsize_bytes;
    r.mem_rss_bytes = s.mem_rss_bytes;
    out.push_back(r);
  }
  return out;
}

procman_lcm::output_t makeOutput(const std::string& deputy_id, int64_t utime,
                                 const std::vector<std::pair<std::string, std::string>>& batch) {
  procman_lcm::output_t m;
  m.utime = utime;
  m.deputy_id = deputy_id;
  for (const auto& [id, text] : batch) {
    m.command_ids.push_back(id);
    m.text.push_back(text);
  }
  m.num_commands = static_cast<int16_t>(m.command_ids.size());
  return m;
}

}  // namespace slide::msg
