#pragma once
// The deputy's bookkeeping of its commands, free of I/O: orders in, actions out. The caller
// carries out each Action (spawn or signal a process) and reports back with markStarted /
// markExited. Times are microseconds on any monotonic-enough clock supplied by the caller.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "procman/command.h"
#include "procman/respawn_backoff.h"

namespace slide::procman {

struct Action {
  enum Kind { kStart, kSignal } kind;
  std::string id;
  int signal = 0;  // for kSignal
};

struct ManagedCommand {
  CommandSpec spec;
  int32_t pid = 0;
  int32_t actual_runid = 0;
  int32_t wanted_runid = 0;   // run id of the last orders
  int32_t exit_code = 0;
  bool should_run = false;
  bool remove_requested = false;
  int64_t kill_deadline_us = 0;  // >0 while stopping: SIGKILL after this time
  bool kill_sent = false;
  int64_t respawn_at_us = 0;     // >0 when an auto-respawn is scheduled
  RespawnBackoff backoff;
};

struct ExitOutcome {
  bool known = false;    // the pid belonged to a command
  std::string id;
  bool removed = false;  // the command was dropped from the table
  std::vector<Action> actions;
};

class ProcessTable {
 public:
  explicit ProcessTable(BackoffParams backoff = {}) : backoff_(backoff) {}

  // Brings the table in line with one orders message (the full desired set). `changed` is set
  // when commands were created, updated or removed, or actions were issued.
  std::vector<Action> applyOrders(const std::vector<DesiredCommand>& orders, int64_t now_us,
                                  bool* changed);
  // Due respawns and SIGKILL escalations.
  std::vector<Action> tick(int64_t now_us);
  // Stops everything (deputy shutdown); SIGKILL follows after at most max_wait_s.
  std::vector<Action> stopAll(int64_t now_us, double max_wait_s);

  void markStarted(const std::string& id, int32_t pid, int64_t now_us);
  void markStartFailed(const std::string& id, int64_t now_us);
  ExitOutcome markExited(int32_t pid, int wait_status, int64_t now_us);

  bool anyRunning() const;
  const std::map<std::string, ManagedCommand>& commands() const { return cmds_; }
  std::vector<CommandReport> reports() const;  // without CPU/memory figures

 private:
  Action beginStop(ManagedCommand& c, int64_t now_us);
  Action startAction(ManagedCommand& c);
  void scheduleRespawn(ManagedCommand& c, int64_t now_us);

  BackoffParams backoff_;
  std::map<std::string, ManagedCommand> cmds_;
};

}  // namespace slide::procman
