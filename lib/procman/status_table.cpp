#include "procman/status_table.h"

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace slide::procman {
namespace {

std::string exitText(const SheriffCommand& c) {
  if (!c.reported || c.report.pid > 0) return "-";
  const int st = c.report.exit_code;
  if (WIFSIGNALED(st)) return "sig" + std::to_string(WTERMSIG(st));
  return std::to_string(WEXITSTATUS(st));
}

}  // namespace

std::string formatStatusTable(const SheriffModel& model) {
  std::vector<std::vector<std::string>> rows{{"DEPUTY", "COMMAND", "GROUP", "STATE", "PID", "RUN", "EXIT", "CPU%", "RSS MB"}};
  for (std::size_t i = 0; i < model.commands().size(); ++i) {
    const SheriffCommand& c = model.commands()[i];
    char cpu[16], rss[16];
    std::snprintf(cpu, sizeof(cpu), "%.1f", c.report.cpu_usage * 100.0);
    std::snprintf(rss, sizeof(rss), "%.1f", c.report.mem_rss_bytes / 1048576.0);
    const bool live = c.reported && c.report.pid > 0;
    rows.push_back({c.deputy, c.spec.id, c.spec.group.empty() ? "-" : c.spec.group,
                    model.heardFrom(c.deputy) ? toString(model.state(i)) : "no deputy",
                    live ? std::to_string(c.report.pid) : "-", std::to_string(c.report.actual_runid), exitText(c),
                    live ? cpu : "-", live ? rss : "-"});
  }
  std::vector<std::size_t> width(rows[0].size(), 0);
  for (const auto& r : rows)
    for (std::size_t k = 0; k < r.size(); ++k) width[k] = std::max(width[k], r[k].size());
  std::string out;
  for (const auto& r : rows) {
    for (std::size_t k = 0; k < r.size(); ++k) {
      out += r[k];
      if (k + 1 < r.size()) out += std::string(width[k] - r[k].size() + 2, ' ');
    }
    out += '\n';
  }
  return out;
}

}  // namespace slide::procman
