#include "procman/process_table.h"

#include <algorithm>
#include <set>

namespace slide::procman {

Action ProcessTable::beginStop(ManagedCommand& c, int64_t now_us) {
  c.respawn_at_us = 0;
  c.kill_deadline_us = now_us + static_cast<int64_t>(c.spec.stop_time_allowed * 1e6);
  c.kill_sent = false;
  return {Action::kSignal, c.spec.id, c.spec.stop_signal};
}

Action ProcessTable::startAction(ManagedCommand& c) {
  c.respawn_at_us = 0;
  return {Action::kStart, c.spec.id, 0};
}

void ProcessTable::scheduleRespawn(ManagedCommand& c, int64_t now_us) {
  c.respawn_at_us = now_us + c.backoff.onExit(now_us) * 1000;
}

std::vector<Action> ProcessTable::applyOrders(const std::vector<DesiredCommand>& orders,
                                              int64_t now_us, bool* changed) {
  std::vector<Action> actions;
  bool any = false;
  std::set<std::string> ordered;
  for (const DesiredCommand& d : orders) {
    ordered.insert(d.spec.id);
    auto it = cmds_.find(d.spec.id);
    if (it == cmds_.end()) {
      ManagedCommand fresh;
      fresh.backoff = RespawnBackoff(backoff_);
      it = cmds_.emplace(d.spec.id, std::move(fresh)).first;
      any = true;
    }
    ManagedCommand& c = it->second;
    const CommandSpec& s = d.spec;
    if (c.spec.exec != s.exec || c.spec.group != s.group || c.spec.auto_respawn != s.auto_respawn ||
        c.spec.stop_signal != s.stop_signal || c.spec.stop_time_allowed != s.stop_time_allowed)
      any = true;
    c.spec = s;  // a new exec string takes effect at the next start
    c.remove_requested = false;
    c.should_run = !d.force_quit;
    c.wanted_runid = d.desired_runid;
    const bool stopping = c.kill_deadline_us > 0;
    if (c.pid == 0) {
      if (c.should_run && c.actual_runid != d.desired_runid) {
        actions.push_back(startAction(c));
      } else if (!c.should_run) {
        c.respawn_at_us = 0;
        if (d.desired_runid != 0) c.actual_runid = d.desired_runid;
      }
    } else if (!c.should_run || (d.desired_runid != c.actual_runid && d.desired_runid != 0)) {
      if (!stopping) actions.push_back(beginStop(c, now_us));
    }
  }
  for (auto& [id, c] : cmds_) {
    if (ordered.count(id) || c.remove_requested) continue;
    any = true;
    c.remove_requested = true;
    c.should_run = false;
    c.respawn_at_us = 0;
    if (c.pid != 0 && c.kill_deadline_us == 0) actions.push_back(beginStop(c, now_us));
  }
  for (auto it = cmds_.begin(); it != cmds_.end();) {
    if (it->second.remove_requested && it->second.pid == 0) it = cmds_.erase(it);
    else ++it;
  }
  if (changed) *changed = any || !actions.empty();
  return actions;
}

std::vector<Action> ProcessTable::tick(int64_t now_us) {
  std::vector<Action> actions;
  for (auto& [id, c] : cmds_) {
    if (c.pid == 0 && c.respawn_at_us > 0 && now_us >= c.respawn_at_us) {
      if (c.should_run && c.spec.auto_respawn && !c.remove_requested) actions.push_back(startAction(c));
      c.respawn_at_us = 0;
    }
    if (c.pid != 0 && c.kill_deadline_us > 0 && !c.kill_sent && now_us >= c.kill_deadline_us) {
      c.kill_sent = true;
      actions.push_back({Action::kSignal, id, SIGKILL});
    }
  }
  return actions;
}

std::vector<Action> ProcessTable::stopAll(int64_t now_us, double max_wait_s) {
  std::vector<Action> actions;
  const int64_t cap = now_us + static_cast<int64_t>(max_wait_s * 1e6);
  for (auto& [id, c] : cmds_) {
    c.should_run = false;
    c.respawn_at_us = 0;
    if (c.pid == 0) continue;
    if (c.kill_deadline_us == 0) actions.push_back(beginStop(c, now_us));
    c.kill_deadline_us = std::min(c.kill_deadline_us, cap);
  }
  return actions;
}

void ProcessTable::markStarted(const std::string& id, int32_t pid, int64_t now_us) {
  auto it = cmds_.find(id);
  if (it == cmds_.end()) return;
  ManagedCommand& c = it->second;
  c.pid = pid;
  c.actual_runid = c.wanted_runid;
  c.exit_code = 0;
  c.kill_deadline_us = 0;
  c.kill_sent = false;
  c.respawn_at_us = 0;
  c.backoff.onStart(now_us);
}

void ProcessTable::markStartFailed(const std::string& id, int64_t now_us) {
  auto it = cmds_.find(id);
  if (it == cmds_.end()) return;
  ManagedCommand& c = it->second;
  c.actual_runid = c.wanted_runid;
  c.exit_code = 127 << 8;  // as a shell reports "command not found"
  c.backoff.onStart(now_us);
  if (c.should_run && c.spec.auto_respawn) scheduleRespawn(c, now_us);
}

ExitOutcome ProcessTable::markExited(int32_t pid, int wait_status, int64_t now_us) {
  ExitOutcome out;
  for (auto it = cmds_.begin(); it != cmds_.end(); ++it) {
    ManagedCommand& c = it->second;
    if (c.pid != pid) continue;
    out.known = true;
    out.id = it->first;
    c.pid = 0;
    c.exit_code = wait_status;
    c.kill_deadline_us = 0;
    c.kill_sent = false;
    if (c.remove_requested) {
      cmds_.erase(it);
      out.removed = true;
    } else if (c.should_run && c.wanted_runid != 0 && c.wanted_runid != c.actual_runid) {
      out.actions.push_back(startAction(c));  // a restart: the stop half is done
    } else if (c.should_run && c.spec.auto_respawn) {
      scheduleRespawn(c, now_us);
    }
    return out;
  }
  return out;
}

bool ProcessTable::anyRunning() const {
  return std::any_of(cmds_.begin(), cmds_.end(), [](const auto& kv) { return kv.second.pid != 0; });
}

std::vector<CommandReport> ProcessTable::reports() const {
  std::vector<CommandReport> out;
  for (const auto& [id, c] : cmds_) {
    CommandReport r;
    r.spec = c.spec;
    r.pid = c.pid;
    r.actual_runid = c.actual_runid;
    r.exit_code = c.exit_code;
    out.push_back(r);
  }
  return out;
}

}  // namespace slide::procman
