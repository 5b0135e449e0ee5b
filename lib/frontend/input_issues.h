#pragma once
// Counts of bad input that was skipped (NaN points, empty scans, missing depth, unknown
// classes...). Library stages count; daemons report the counts in rate-limited warnings.
#include <map>
#include <optional>
#include <string>

namespace slide::frontend {

class InputIssues {
 public:
  void count(const std::string& reason, long n = 1) {
    if (n > 0) counts_[reason] += n;
  }
  bool empty() const { return counts_.empty(); }
  long total() const;
  long get(const std::string& reason) const;
  const std::map<std::string, long>& counts() const { return counts_; }
  void merge(const InputIssues& other);
  void clear() { counts_.clear(); }
  // "reason: n, reason: n" in name order.
  std::string summary() const;

 private:
  std::map<std::string, long> counts_;
};

}  // namespace slide::frontend

namespace slide::frontend {

// Collects issues between reports so a daemon warns at most once per interval with the counts
// since its last warning (and the running totals).
class IssueWindow {
 public:
  explicit IssueWindow(double interval_s = 5.0) : interval_s_(interval_s) {}
  void add(const InputIssues& issues) {
    pending_.merge(issues);
    total_.merge(issues);
  }
  // The text of a warning when one is due at time now_s (seconds, any monotonic clock), and
  // then starts a new window; nullopt otherwise.
  std::optional<std::string> due(double now_s);
  const InputIssues& total() const { return total_; }

 private:
  double interval_s_;
  double last_s_ = -1e300;
  InputIssues pending_, total_;
};

}  // namespace slide::frontend
