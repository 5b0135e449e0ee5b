#include "procman/script_runner.h"

#include <sys/wait.h>

#include <algorithm>

namespace slide::procman {
namespace {

std::string describeExit(int st) {
  if (WIFSIGNALED(st)) return "signal " + std::to_string(WTERMSIG(st));
  return "status " + std::to_string(WEXITSTATUS(st));
}

}  // namespace

ScriptRunner::ScriptRunner(const PmdConfig& cfg, SheriffModel& model, const std::string& script,
                           double wait_timeout_s)
    : model_(model), file_(cfg.file), timeout_s_(wait_timeout_s), expected_(model.commands().size(), WaitStatus::kNone) {
  const PmdScript* s = cfg.findScript(script);
  if (!s) {
    std::string known;
    for (const PmdScript& k : cfg.scripts) known += (known.empty() ? "" : ", ") + k.name;
    throw PmdError(cfg.file, {0, 0}, "no script named '" + script + "' (scripts: " + (known.empty() ? "none" : known) + ")");
  }
  std::vector<std::string> stack;
  flatten(cfg, *s, stack);
}

void ScriptRunner::flatten(const PmdConfig& cfg, const PmdScript& s, std::vector<std::string>& stack) {
  if (std::find(stack.begin(), stack.end(), s.name) != stack.end())
    throw PmdError(cfg.file, s.pos, "script '" + s.name + "' runs itself through run_script");
  stack.push_back(s.name);
  for (const ScriptAction& a : s.actions) {
    if (a.kind == ScriptAction::kRunScript) {
      const PmdScript* sub = cfg.findScript(a.name);
      if (!sub) throw PmdError(cfg.file, a.pos, "run_script: no script named '" + a.name + "'");
      flatten(cfg, *sub, stack);
      continue;
    }
    Step st{a, {}};
    if (a.kind != ScriptAction::kWaitMs) {
      st.targets = model_.select(a.target, a.name);
      if (st.targets.empty())
        throw PmdError(cfg.file, a.pos, std::string(a.target == TargetKind::kGroup ? "no group" : "no command") +
                                            " named '" + a.name + "'");
    }
    steps_.push_back(st);
  }
  stack.pop_back();
}

bool ScriptRunner::reached(std::size_t i, WaitStatus w) const {
  const CommandState s = model_.state(i);
  if (w == WaitStatus::kRunning) return s == CommandState::kRunning;
  return s == CommandState::kStoppedOk || s == CommandState::kStoppedError;
}

std::string ScriptRunner::describe(const Step& st) const {
  const ScriptAction& a = st.action;
  static const char* verbs[] = {"start", "stop", "restart", "wait ms", "wait", "run_script"};
  std::string s = verbs[a.kind];
  if (a.kind == ScriptAction::kWaitMs) return s + " " + std::to_string(a.ms);
  s += a.target == TargetKind::kEverything ? " everything" : a.target == TargetKind::kGroup ? " group " + a.name : " cmd " + a.name;
  if (a.wait != WaitStatus::kNone) s += std::string(" (wait ") + toString(a.wait) + ")";
  return s;
}

ScriptRunner::Result ScriptRunner::checkWait(const std::vector<std::size_t>& targets, WaitStatus w,
                                             int64_t now_us, const std::string& what) {
  std::vector<std::string> bad;
  bool all = true;
  for (std::size_t i : targets) {
    if (reached(i, w)) continue;
    all = false;
    const SheriffCommand& c = model_.commands()[i];
    if (w == WaitStatus::kRunning && model_.exitedForGood(i))
      bad.push_back(c.deputy + "/" + c.spec.id + " exited (" + describeExit(c.report.exit_code) + ")");
  }
  if (all) return Result::kDone;
  if (bad.empty() && now_us < deadline_us_) return Result::kRunning;
  if (bad.empty()) {
    for (std::size_t i : targets)
      if (!reached(i, w)) {
        const SheriffCommand& c = model_.commands()[i];
        bad.push_back(c.deputy + "/" + c.spec.id + " is " + toString(model_.state(i)));
      }
  }
  for (const std::string& b : bad) {
    failures_.push_back(what + ": " + b + ", not " + toString(w));
    messages_.push_back("FAILED " + failures_.back());
  }
  return Result::kFailed;
}

ScriptRunner::Result ScriptRunner::step(int64_t now_us, bool* orders_changed) {
  if (orders_changed) *orders_changed = false;
  if (!failures_.empty()) return Result::kFailed;
  while (next_ < steps_.size()) {
    const Step& st = steps_[next_];
    const ScriptAction& a = st.action;
    if (!waiting_) {
      messages_.push_back(describe(st));
      if (a.kind == ScriptAction::kStart || a.kind == ScriptAction::kStop || a.kind == ScriptAction::kRestart) {
        for (std::size_t i : st.targets) {
          if (a.kind == ScriptAction::kStart) model_.start(i);
          else if (a.kind == ScriptAction::kStop) model_.stop(i);
          else model_.restart(i);
          expected_[i] = a.kind == ScriptAction::kStop ? WaitStatus::kStopped : WaitStatus::kRunning;
        }
        if (orders_changed) *orders_changed = true;
        if (a.wait == WaitStatus::kNone) {
          ++next_;
          continue;
        }
      }
      waiting_ = true;
      deadline_us_ = now_us + (a.kind == ScriptAction::kWaitMs ? a.ms * 1000 : static_cast<int64_t>(timeout_s_ * 1e6));
    }
    Result r;
    if (a.kind == ScriptAction::kWaitMs) r = now_us >= deadline_us_ ? Result::kDone : Result::kRunning;
    else r = checkWait(st.targets, a.wait, now_us, file_ + ":" + std::to_string(a.pos.line) + " " + describe(st));
    if (r != Result::kDone) return r;
    waiting_ = false;
    ++next_;
  }
  // Final check: everything the script touched is where it was last sent.
  if (next_ == steps_.size()) {
    deadline_us_ = now_us + static_cast<int64_t>(timeout_s_ * 1e6);
    ++next_;
    messages_.push_back("checking final states");
  }
  for (WaitStatus w : {WaitStatus::kRunning, WaitStatus::kStopped}) {
    std::vector<std::size_t> targets;
    for (std::size_t i = 0; i < expected_.size(); ++i)
      if (expected_[i] == w) targets.push_back(i);
    const Result r = checkWait(targets, w, now_us, "end of script");
    if (r != Result::kDone) return r;
  }
  return Result::kDone;
}

std::vector<std::string> ScriptRunner::takeMessages() {
  std::vector<std::string> out;
  out.swap(messages_);
  return out;
}

}  // namespace slide::procman
