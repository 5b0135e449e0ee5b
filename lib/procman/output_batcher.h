#pragma once
// Collects console output per command and releases it in batches, so a chatty child costs a
// few messages per second instead of one per write.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace slide::procman {

class OutputBatcher {
 public:
  OutputBatcher(std::size_t max_bytes = 4096, int64_t max_delay_us = 20'000)
      : max_bytes_(max_bytes), max_delay_us_(max_delay_us) {}

  void add(const std::string& command_id, const std::string& text, int64_t now_us);
  bool empty() const { return entries_.empty(); }
  // True when the pending output is large or old enough to send.
  bool due(int64_t now_us) const;
  // Pending output as (command id, text) pairs in first-seen order; clears the batch.
  std::vector<std::pair<std::string, std::string>> take();

 private:
  std::size_t max_bytes_;
  int64_t max_delay_us_;
  std::vector<std::pair<std::string, std::string>> entries_;
  std::size_t bytes_ = 0;
  int64_t first_us_ = 0;
};

}  // namespace slide::procman
