#include "procman/proc_stats.h"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <vector>

namespace slide::procman {
namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) return {};
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

std::optional<ProcessTimes> parseProcessStat(const std::string& text, int64_t page_size) {
  // The command name (field 2) is in parentheses and may hold spaces: parse after the last ')'.
  const std::size_t close = text.rfind(')');
  if (close == std::string::npos) return std::nullopt;
  std::istringstream in(text.substr(close + 1));
  std::vector<std::string> f;  // f[0] is field 3 (state)
  for (std::string w; in >> w;) f.push_back(w);
  if (f.size() < 22) return std::nullopt;
  try {
    ProcessTimes t;
    t.user_jiffies = std::stoull(f[11]);    // field 14 utime
    t.system_jiffies = std::stoull(f[12]);  // field 15 stime
    t.vsize_bytes = std::stoll(f[20]);      // field 23 vsize
    t.rss_bytes = std::stoll(f[21]) * page_size;  // field 24 rss (pages)
    return t;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<SystemTimes> parseSystemStat(const std::string& text) {
  std::istringstream in(text);
  std::string label;
  uint64_t user = 0, nice = 0, system = 0, idle = 0;
  if (!(in >> label >> user >> nice >> system >> idle) || label != "cpu") return std::nullopt;
  SystemTimes t;
  t.busy_jiffies = user + nice + system;
  t.total_jiffies = t.busy_jiffies + idle;
  return t;
}

MemoryInfo parseMeminfo(const std::string& text) {
  MemoryInfo m;
  int64_t mem_free = -1, available = -1;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    std::string key;
    int64_t kb = 0;
    if (!(ls >> key >> kb)) continue;
    if (key == "MemTotal:") m.total_bytes = kb * 1024;
    else if (key == "MemFree:") mem_free = kb * 1024;
    else if (key == "MemAvailable:") available = kb * 1024;
    else if (key == "SwapTotal:") m.swap_total_bytes = kb * 1024;
    else if (key == "SwapFree:") m.swap_free_bytes = kb * 1024;
  }
  m.free_bytes = available >= 0 ? available : (mem_free >= 0 ? mem_free : 0);
  return m;
}

float cpuShare(uint64_t used_before, uint64_t used_after, const SystemTimes& before,
               const SystemTimes& after) {
  if (after.total_jiffies <= before.total_jiffies || used_after < used_before) return 0.f;
  const double share = double(used_after - used_before) / double(after.total_jiffies - before.total_jiffies);
  return share > 1.0 ? 1.f : static_cast<float>(share);
}

std::optional<ProcessTimes> readProcessTimes(int pid) {
  return parseProcessStat(readFile("/proc/" + std::to_string(pid) + "/stat"), sysconf(_SC_PAGESIZE));
}

std::optional<SystemTimes> readSystemTimes() { return parseSystemStat(readFile("/proc/stat")); }

MemoryInfo readMemoryInfo() { return parseMeminfo(readFile("/proc/meminfo")); }

}  // namespace slide::procman
