#include "msg/status_beacon.h"

#include "app/clock.h"
#include "slide/daemon_status_t.hpp"

namespace slide::msg {

StatusBeacon::StatusBeacon(lcm::LCM& lcm, std::string channel, int robot, std::string daemon, double period_s)
    : lcm_(lcm),
      channel_(std::move(channel)),
      daemon_(std::move(daemon)),
      robot_(robot),
      period_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(period_s))) {}

void StatusBeacon::tick(std::int64_t published, std::int64_t dropped_messages, std::int64_t dropped_inputs, bool now) {
  const auto t = std::chrono::steady_clock::now();
  if (!now && last_.time_since_epoch().count() != 0 && t - last_ < period_) return;
  last_ = t;
  daemon_status_t s;
  s.utime = app::wallMicros();
  s.robot = robot_;
  s.daemon = daemon_;
  s.published = published;
  s.dropped_messages = dropped_messages;
  s.dropped_inputs = dropped_inputs;
  lcm_.publish(channel_, &s);
}

}  // namespace slide::msg
