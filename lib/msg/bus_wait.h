#pragma once
// One wait over several LCM buses (a daemon on the robot bus and the team bus, the viewer on
// any number): up to `timeout_us` for a datagram on any of them, then one handle() per bus that
// has one; with no bus, a sleep of `timeout_us`. An interrupted wait (a signal) returns early;
// nothing is thrown.
#include <cstdint>
#include <vector>

namespace lcm {
class LCM;
}

namespace slide::msg {

void handleAny(const std::vector<lcm::LCM*>& buses, std::int64_t timeout_us);

}  // namespace slide::msg
