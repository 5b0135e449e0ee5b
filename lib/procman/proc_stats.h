#pragma once
// CPU and memory figures from Linux /proc: parsers of the text (testable) and readers.
#include <cstdint>
#include <optional>
#include <string>

namespace slide::procman {

struct ProcessTimes {
  uint64_t user_jiffies = 0;
  uint64_t system_jiffies = 0;
  int64_t vsize_bytes = 0;
  int64_t rss_bytes = 0;
};

struct SystemTimes {
  uint64_t busy_jiffies = 0;   // user + nice + system
  uint64_t total_jiffies = 0;  // busy + idle
};

struct MemoryInfo {
  int64_t total_bytes = 0, free_bytes = 0, swap_total_bytes = 0, swap_free_bytes = 0;
};

// /proc/<pid>/stat text; nullopt when malformed. page_size converts rss pages to bytes.
std::optional<ProcessTimes> parseProcessStat(const std::string& text, int64_t page_size);
// /proc/stat text (the aggregate "cpu" line); nullopt when malformed.
std::optional<SystemTimes> parseSystemStat(const std::string& text);
// /proc/meminfo text; "free" is MemAvailable when present, else MemFree.
MemoryInfo parseMeminfo(const std::string& text);

// Share of the host's CPU used between two samples, in [0, 1] (0 when undefined).
float cpuShare(uint64_t used_before, uint64_t used_after, const SystemTimes& before,
               const SystemTimes& after);

std::optional<ProcessTimes> readProcessTimes(int pid);
std::optional<SystemTimes> readSystemTimes();
MemoryInfo readMemoryInfo();

}  // namespace slide::procman
