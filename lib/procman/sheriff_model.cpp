#include "procman/sheriff_model.h"

#include <sys/wait.h>

#include <algorithm>

namespace slide::procman {

const char* toString(CommandState s) {
  switch (s) {
    case CommandState::kUnknown: return "unknown";
    case CommandState::kStarting: return "starting";
    case CommandState::kRunning: return "running";
    case CommandState::kStopping: return "stopping";
    case CommandState::kRestarting: return "restarting";
    case CommandState::kStoppedOk: return "stopped (ok)";
    case CommandState::kStoppedError: return "stopped (error)";
  }
  return "?";
}

SheriffModel::SheriffModel(const std::vector<PmdCommand>& commands) {
  for (const PmdCommand& pc : commands) {
    SheriffCommand c;
    c.deputy = pc.deputy;
    c.spec = pc.spec;
    cmds_.push_back(c);
  }
}

void SheriffModel::onDeputyInfo(const std::string& deputy, const std::vector<CommandReport>& reports) {
  if (!heardFrom(deputy)) heard_.push_back(deputy);
  for (SheriffCommand& c : cmds_) {
    if (c.deputy != deputy) continue;
    auto it = std::find_if(reports.begin(), reports.end(), [&](const CommandReport& r) { return r.spec.id == c.spec.id; });
    if (it == reports.end()) {
      // The deputy does not hold it (it has not accepted our orders, or not yet): whatever
      // runs there is unknown, and a script waiting for any state must not see it reached.
      c.reported = false;
      c.report = CommandReport{};
      c.report.spec = c.spec;
      if (!c.ordered) c.force_quit = true;
      continue;
    }
    if (!c.ordered && !c.adopted) {
      c.desired_runid = it->actual_runid;
      c.force_quit = it->pid == 0 && !c.spec.auto_respawn;
    }
    c.adopted = true;
    c.reported = true;
    c.report = *it;
  }
}

bool SheriffModel::heardFrom(const std::string& deputy) const {
  return std::find(heard_.begin(), heard_.end(), deputy) != heard_.end();
}

void SheriffModel::bumpRunid(SheriffCommand& c) {
  c.desired_runid = std::max(c.desired_runid, c.report.actual_runid) + 1;
  if (c.desired_runid <= 0) c.desired_runid = 1;
}

void SheriffModel::start(std::size_t i) {
  SheriffCommand& c = cmds_[i];
  c.ordered = true;
  if (state(i) == CommandState::kRunning) return;
  if (c.force_quit || c.report.pid == 0) bumpRunid(c);
  c.force_quit = false;
}

void SheriffModel::stop(std::size_t i) {
  cmds_[i].ordered = true;
  cmds_[i].force_quit = true;
}

void SheriffModel::restart(std::size_t i) {
  SheriffCommand& c = cmds_[i];
  c.ordered = true;
  bumpRunid(c);
  c.force_quit = false;
}

std::vector<std::size_t> SheriffModel::select(TargetKind kind, const std::string& name) const {
  std::vector<std::size_t> out;
  const std::string group = name.empty() || name.back() != '/' ? name : name.substr(0, name.size() - 1);
  for (std::size_t i = 0; i < cmds_.size(); ++i) {
    const CommandSpec& s = cmds_[i].spec;
    const bool hit = kind == TargetKind::kEverything ||
                     (kind == TargetKind::kCommand && s.id == name) ||
                     (kind == TargetKind::kGroup && (s.group == group || s.group.rfind(group + "/", 0) == 0));
    if (hit) out.push_back(i);
  }
  return out;
}

std::vector<std::string> SheriffModel::deputies() const {
  std::vector<std::string> out;
  for (const SheriffCommand& c : cmds_)
    if (std::find(out.begin(), out.end(), c.deputy) == out.end()) out.push_back(c.deputy);
  return out;
}

std::vector<DesiredCommand> SheriffModel::ordersFor(const std::string& deputy) const {
  std::vector<DesiredCommand> out;
  for (const SheriffCommand& c : cmds_)
    if (c.deputy == deputy) out.push_back({c.spec, c.desired_runid, c.force_quit});
  return out;
}

CommandState SheriffModel::state(std::size_t i) const {
  const SheriffCommand& c = cmds_[i];
  if (!c.reported) return CommandState::kUnknown;
  const CommandReport& r = c.report;
  if (c.force_quit) {
    if (r.pid > 0) return CommandState::kStopping;
  } else if (c.desired_runid != r.actual_runid) {
    return r.pid > 0 ? CommandState::kRestarting : CommandState::kStarting;
  } else if (r.pid > 0) {
    return CommandState::kRunning;
  }
  const int st = r.exit_code;
  if (st == 0) return CommandState::kStoppedOk;
  if (c.force_quit && WIFSIGNALED(st)) {
    const int sig = WTERMSIG(st);
    if (sig == SIGINT || sig == SIGTERM || sig == SIGKILL || sig == c.spec.stop_signal) return CommandState::kStoppedOk;
  }
  return CommandState::kStoppedError;
}

bool SheriffModel::exitedForGood(std::size_t i) const {
  const CommandState s = state(i);
  const SheriffCommand& c = cmds_[i];
  return (s == CommandState::kStoppedOk || s == CommandState::kStoppedError) && !c.force_quit &&
         !c.spec.auto_respawn && c.desired_runid == c.report.actual_runid;
}

}  // namespace slide::procman
