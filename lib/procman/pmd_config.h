#pragma once
// procman's sheriff configuration language (.pmd / .cfg):
//   group "name" { cmd "id" { exec = "..."; deputy = "robot1"; auto_respawn = "true";
//                             stop_signal = 15; stop_time_allowed = 5; } group "sub" {...} }
//   script "name" { start cmd "id" wait "running"; stop group "g"; restart everything;
//                   wait ms 500; wait cmd "id" status "stopped"; run_script "other"; }
// `host` is accepted as the older spelling of `deputy`. Errors name file, line and column.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "procman/command.h"

namespace slide::procman {

struct SourcePos {
  int line = 0, column = 0;
};

class PmdError : public std::runtime_error {
 public:
  PmdError(const std::string& file, SourcePos pos, const std::string& what);
  SourcePos pos;
};

struct PmdCommand {
  CommandSpec spec;  // spec.group is the full path, e.g. "robot1/frontend"
  std::string deputy;
  SourcePos pos;
};

enum class TargetKind { kEverything, kGroup, kCommand };
enum class WaitStatus { kNone, kRunning, kStopped };

struct ScriptAction {
  enum Kind { kStart, kStop, kRestart, kWaitMs, kWaitStatus, kRunScript } kind = kStart;
  TargetKind target = TargetKind::kEverything;
  std::string name;  // command id, group path or script name
  WaitStatus wait = WaitStatus::kNone;
  int64_t ms = 0;
  SourcePos pos;
};

struct PmdScript {
  std::string name;
  std::vector<ScriptAction> actions;
  SourcePos pos;
};

struct PmdConfig {
  std::string file;
  std::vector<PmdCommand> commands;
  std::vector<PmdScript> scripts;
  const PmdScript* findScript(const std::string& name) const;
};

// Parses config text; `file` names the source in errors. Throws PmdError.
PmdConfig parsePmd(const std::string& text, const std::string& file);
// Reads and parses a file. Throws PmdError (also for an unreadable file).
PmdConfig loadPmd(const std::string& path);

const char* toString(WaitStatus s);

}  // namespace slide::procman
