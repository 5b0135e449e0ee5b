#pragma once
// Delay before an auto-respawn: doubles each time a command is started again soon after its
// previous start (it keeps crashing), capped; falls back to the minimum once a run lasted.
#include <cstdint>

namespace slide::procman {

struct BackoffParams {
  int64_t min_ms = 100;
  int64_t max_ms = 5000;
  int64_t settled_ms = 10000;  // a run this long resets the delay to min_ms
};

class RespawnBackoff {
 public:
  explicit RespawnBackoff(BackoffParams p = {}) : p_(p), delay_ms_(p.min_ms) {}
  // Records a start at now_us and updates the delay for the next respawn.
  void onStart(int64_t now_us);
  int64_t delayMs() const { return delay_ms_; }

 private:
  BackoffParams p_;
  int64_t delay_ms_;
  int64_t last_start_us_ = -1;
};

}  // namespace slide::procman
