#include "procman/respawn_backoff.h"

#include <algorithm>

namespace slide::procman {

int64_t RespawnBackoff::onExit(int64_t now_us) {
  if (last_start_us_ < 0 || now_us - last_start_us_ >= p_.settled_ms * 1000) delay_ms_ = p_.min_ms;
  const int64_t delay = delay_ms_;
  delay_ms_ = std::min(p_.max_ms, delay_ms_ * 2);
  return delay;
}

}  // namespace slide::procman
