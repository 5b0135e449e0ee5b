#pragma once
// One wait over several LCM buses (a daemon on the robot bus and the team bus): up to
// `timeout_us` for a datagram on any of them, then one handle() per bus that has one. An
// interrupted wait (a signal) returns early; nothing is thrown.
#include <cstdint>
#include <initializer_list>

namespace lcm {
class LCM;
}

namespace slide::msg {

void handleAny(std::initializer_list<lcm::LCM*> buses, std::int64_t timeout_us);

}  // namespace slide::msg
