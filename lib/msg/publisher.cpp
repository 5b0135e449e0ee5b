#include "msg/publisher.h"

#include <lcm/lcm-cpp.hpp>

namespace slide::msg {

Publisher lcmPublisher(lcm::LCM& lcm) {
  return [&lcm](const std::string& channel, const std::vector<uint8_t>& bytes) {
    return lcm.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size())) == 0;
  };
}

Publisher lcmPublisher(lcm::LCM* lcm) { return lcm ? lcmPublisher(*lcm) : Publisher(); }

}  // namespace slide::msg
