#pragma once
// A daemon's counts on the bus: daemon_status_t every `period_s` (and once more at stop), so
// that drops are seen by lcm-spy, the deputy's operator and tests, not only in a log.
#include <lcm/lcm-cpp.hpp>
#include <chrono>
#include <cstdint>
#include <string>

namespace slide::msg {

class StatusBeacon {
 public:
  StatusBeacon(lcm::LCM& lcm, std::string channel, int robot, std::string daemon, double period_s = 5.0);
  // Sends the totals when the period has passed since the last time, or when `now` is set.
  void tick(std::int64_t published, std::int64_t dropped_messages, std::int64_t dropped_inputs, bool now = false);

 private:
  lcm::LCM& lcm_;
  std::string channel_, daemon_;
  int robot_;
  std::chrono::steady_clock::duration period_;
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace slide::msg
