#pragma once
// How a daemon's node sends: it is given a Publisher, so that its logic runs and is tested
// without a bus. publish(channel, bytes) sends one encoded message and returns false when the
// bus refused it. A daemon's main makes one with lcmPublisher; a test collects the bytes.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace lcm {
class LCM;
}

namespace slide::msg {

using Publisher = std::function<bool(const std::string& channel, const std::vector<uint8_t>& bytes)>;

// Publishes on `lcm` (which must outlive the publisher); on null, an empty publisher.
Publisher lcmPublisher(lcm::LCM& lcm);
Publisher lcmPublisher(lcm::LCM* lcm);

// The bytes of an lcm-gen message.
template <typename M>
std::vector<uint8_t> encodeLcm(const M& m) {
  std::vector<uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

}  // namespace slide::msg
