#pragma once
// The plain description of a procman command, what a sheriff wants of it and what a deputy
// reports about it. Mirrors procman_lcm's cmd_t / cmd_desired_t / cmd_status_t without LCM.
#include <csignal>
#include <cstdint>
#include <string>

namespace slide::procman {

struct CommandSpec {
  std::string id;                  // unique within a deputy
  std::string exec;                // program and arguments (see exec_args.h)
  std::string group;               // slash-separated group path, may be empty
  bool auto_respawn = false;
  int stop_signal = SIGINT;
  double stop_time_allowed = 7.0;  // seconds between the stop signal and SIGKILL
};

struct DesiredCommand {
  CommandSpec spec;
  int32_t desired_runid = 0;  // a value different from the deputy's run id asks for a start
  bool force_quit = false;    // the command must not run
};

struct CommandReport {
  CommandSpec spec;
  int32_t pid = 0;            // 0 when not running
  int32_t actual_runid = 0;
  int32_t exit_code = 0;      // raw wait status of the last run
  float cpu_usage = 0.f;      // [0, 1] of the whole host
  int64_t mem_vsize_bytes = 0;
  int64_t mem_rss_bytes = 0;
};

// Orders older than this (by their sender's clock) are ignored, as procman does.
constexpr int64_t kMaxOrderAgeUs = 60'000'000;
inline bool ordersAreStale(int64_t order_utime, int64_t now_us) {
  return now_us - order_utime > kMaxOrderAgeUs;
}

}  // namespace slide::procman
