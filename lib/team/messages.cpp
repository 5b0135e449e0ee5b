#include "team/messages.h"

#include <algorithm>

namespace slide::team {
namespace {
constexpr std::size_t kFingerprint = 8;

std::size_t rangesSize(const OriginRanges& r) {
  std::size_t n = 2;  // num_origins
  for (const auto& [origin, set] : r) n += 2 + 2 + 8 * set.ranges().size();
  return n;
}
}  // namespace

std::size_t encodedSize(const Heartbeat& m) {
  return kFingerprint + 2 + 8 + rangesSize(m.held) + 2 + 6 * m.maps.size() + 1 + m.mac.size();
}
std::size_t encodedSize(const Chunk& m) { return kFingerprint + 2 + 2 + 8 + 1 + 2 + 4 + 2 + 2 + 2 + m.data.size() + 1 + m.mac.size(); }
std::size_t encodedSize(const Ack& m) { return kFingerprint + 2 + 2 + 8 + rangesSize(m.acked) + 1 + m.mac.size(); }

namespace {

// IPv4 bytes of one UDP datagram carrying `udp_payload` bytes.
std::size_t ipBytes(std::size_t udp_payload, std::size_t mtu) {
  constexpr std::size_t kUdp = 8, kIp = 20;
  const std::size_t per_packet = (mtu - kIp) / 8 * 8;  // IP fragments carry multiples of 8 bytes
  const std::size_t udp = kUdp + udp_payload;
  const std::size_t packets = (udp + per_packet - 1) / per_packet;
  return udp + packets * kIp;
}

}  // namespace

std::size_t lcmWireBytes(const std::string& channel, std::size_t payload, std::size_t mtu) {
  constexpr std::size_t kShortHeader = 8, kShortMax = 65499, kFragmentHeader = 20, kFragmentMax = 65487;
  const std::size_t named = channel.size() + 1;
  if (named + payload <= kShortMax) return ipBytes(kShortHeader + named + payload, mtu);
  std::size_t bytes = 0, left = named + payload;  // the channel travels in the first fragment
  while (left > 0) {
    const std::size_t part = std::min(left, kFragmentMax);
    bytes += ipBytes(kFragmentHeader + part, mtu);
    left -= part;
  }
  return bytes;
}

}  // namespace slide::team
