#pragma once
// A sheriff's view of the team: what it wants of every configured command and what the
// deputies last reported, and the procman status derived from both. No I/O.
#include <cstdint>
#include <string>
#include <vector>

#include "procman/command.h"
#include "procman/pmd_config.h"

namespace slide::procman {

enum class CommandState { kUnknown, kStarting, kRunning, kStopping, kRestarting, kStoppedOk, kStoppedError };
const char* toString(CommandState s);

struct SheriffCommand {
  std::string deputy;
  CommandSpec spec;
  int32_t desired_runid = 0;
  bool force_quit = false;
  bool ordered = false;   // the sheriff has changed its desired state
  bool reported = false;  // a deputy report for it has arrived
  bool adopted = false;   // its deputy has reported it (run id taken over unless ordered)
  CommandReport report;
};

class SheriffModel {
 public:
  explicit SheriffModel(const std::vector<PmdCommand>& commands);

  // Applies one PM_INFO. A command's first report adopts its run id (unless the sheriff already
  // gave an order), so a sheriff joining running deputies restarts nothing.
  void onDeputyInfo(const std::string& deputy, const std::vector<CommandReport>& reports);
  bool heardFrom(const std::string& deputy) const;

  void start(std::size_t i);
  void stop(std::size_t i);
  void restart(std::size_t i);

  // Indices of the commands an action target names (empty when none match).
  std::vector<std::size_t> select(TargetKind kind, const std::string& name) const;
  std::vector<std::string> deputies() const;
  std::vector<DesiredCommand> ordersFor(const std::string& deputy) const;

  CommandState state(std::size_t i) const;
  // Stopped by itself with its current run finished and nothing to bring it back.
  bool exitedForGood(std::size_t i) const;
  const std::vector<SheriffCommand>& commands() const { return cmds_; }

 private:
  void bumpRunid(SheriffCommand& c);
  std::vector<SheriffCommand> cmds_;
  std::vector<std::string> heard_;
};

}  // namespace slide::procman
