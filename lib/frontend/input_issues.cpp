#include "frontend/input_issues.h"

namespace slide::frontend {

long InputIssues::total() const {
  long n = 0;
  for (const auto& [reason, c] : counts_) n += c;
  return n;
}

long InputIssues::get(const std::string& reason) const {
  const auto it = counts_.find(reason);
  return it == counts_.end() ? 0 : it->second;
}

void InputIssues::merge(const InputIssues& other) {
  for (const auto& [reason, c] : other.counts_) counts_[reason] += c;
}

std::string InputIssues::summary() const {
  std::string s;
  for (const auto& [reason, c] : counts_) {
    if (!s.empty()) s += ", ";
    s += reason + ": " + std::to_string(c);
  }
  return s;
}

}  // namespace slide::frontend

namespace slide::frontend {

std::optional<std::string> IssueWindow::due(double now_s) {
  if (pending_.empty() || now_s - last_s_ < interval_s_) return std::nullopt;
  last_s_ = now_s;
  std::string s = "skipped bad input: " + pending_.summary() + " (total " + std::to_string(total_.total()) + ")";
  pending_.clear();
  return s;
}

}  // namespace slide::frontend
