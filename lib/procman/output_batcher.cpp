#include "procman/output_batcher.h"

namespace slide::procman {

void OutputBatcher::add(const std::string& command_id, const std::string& text, int64_t now_us) {
  if (text.empty()) return;
  if (entries_.empty()) first_us_ = now_us;
  bytes_ += text.size();
  for (auto& [id, t] : entries_) {
    if (id == command_id) {
      t += text;
      return;
    }
  }
  entries_.emplace_back(command_id, text);
}

bool OutputBatcher::due(int64_t now_us) const {
  return !entries_.empty() && (bytes_ >= max_bytes_ || now_us - first_us_ >= max_delay_us_);
}

std::vector<std::pair<std::string, std::string>> OutputBatcher::take() {
  std::vector<std::pair<std::string, std::string>> out;
  out.swap(entries_);
  bytes_ = 0;
  return out;
}

}  // namespace slide::procman
