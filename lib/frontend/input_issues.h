#pragma once
// Counts of bad input that was skipped (NaN points, empty scans, missing depth, unknown
// classes...). Library stages count; daemons report the counts in rate-limited warnings.
#include <map>
#include <string>

namespace slide {

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

}  // namespace slide
