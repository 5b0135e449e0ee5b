#pragma once
// Token bucket over bytes: `rate` bytes per second refill, up to `burst` bytes banked.
#include <algorithm>
#include <cstdint>

namespace slide::team {

using Micros = std::int64_t;

class RateLimiter {
 public:
  RateLimiter(double bytes_per_s, double burst_bytes) : rate_(bytes_per_s), burst_(burst_bytes), tokens_(burst_bytes) {}

  // True when `bytes` may be sent now (and takes them). A message larger than the burst is
  // let through whenever the bucket is full, so nothing is blocked for ever.
  bool tryTake(double bytes, Micros now) {
    refill(now);
    if (tokens_ >= bytes || tokens_ >= burst_) {
      tokens_ -= bytes;
      return true;
    }
    return false;
  }
  // Takes `bytes` unconditionally (control traffic); the bucket may go negative.
  void force(double bytes, Micros now) {
    refill(now);
    tokens_ -= bytes;
  }
  double tokens(Micros now) {
    refill(now);
    return tokens_;
  }

 private:
  void refill(Micros now) {
    if (last_ >= 0 && now > last_) tokens_ = std::min(burst_, tokens_ + rate_ * 1e-6 * static_cast<double>(now - last_));
    last_ = std::max(last_, now);
  }
  double rate_, burst_, tokens_;
  Micros last_ = -1;
};

}  // namespace slide::team
