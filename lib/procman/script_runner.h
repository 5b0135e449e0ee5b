#pragma once
// Runs one script of a .pmd config against a SheriffModel, step by step: the caller feeds
// deputy reports into the model, calls step() often, and sends orders when they changed.
// After the last action it waits until every command the script touched is in the state
// the script last asked for; a wait that times out or a command that exits for good fails.
#include <cstdint>
#include <string>
#include <vector>

#include "procman/pmd_config.h"
#include "procman/sheriff_model.h"

namespace slide::procman {

class ScriptRunner {
 public:
  enum class Result { kRunning, kDone, kFailed };

  // Throws PmdError for an unknown script, an unknown cmd/group target or run_script recursion.
  ScriptRunner(const PmdConfig& cfg, SheriffModel& model, const std::string& script, double wait_timeout_s);

  Result step(int64_t now_us, bool* orders_changed);
  // Progress and failure lines produced since the last call.
  std::vector<std::string> takeMessages();
  const std::vector<std::string>& failures() const { return failures_; }

 private:
  struct Step {
    ScriptAction action;
    std::vector<std::size_t> targets;
  };
  void flatten(const PmdConfig& cfg, const PmdScript& s, std::vector<std::string>& stack);
  bool reached(std::size_t i, WaitStatus w) const;
  // Checks the pending wait; returns kRunning while it must go on.
  Result checkWait(const std::vector<std::size_t>& targets, WaitStatus w, int64_t now_us, const std::string& what);
  std::string describe(const Step& st) const;

  SheriffModel& model_;
  std::string file_;
  double timeout_s_;
  std::vector<Step> steps_;
  std::size_t next_ = 0;
  bool waiting_ = false;
  int64_t deadline_us_ = 0;
  std::vector<WaitStatus> expected_;  // per command: last state asked, kNone if untouched
  std::vector<std::string> messages_, failures_;
};

}  // namespace slide::procman
