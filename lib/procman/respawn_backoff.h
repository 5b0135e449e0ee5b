#pragma once
// Delay before an auto-respawn: doubles with each exit that follows its start quickly (the
// command keeps crashing), capped; falls back to the minimum once a run lasted settled_ms.
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
  void onStart(int64_t now_us) { last_start_us_ = now_us; }
  // The delay before respawning a command that exited (or failed to start) at now_us.
  int64_t onExit(int64_t now_us);

 private:
  BackoffParams p_;
  int64_t delay_ms_;
  int64_t last_start_us_ = -1;
};

}  // namespace slide::procman
