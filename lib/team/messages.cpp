#include "team/messages.h"

namespace slide::team {
namespace {
constexpr std::size_t kFingerprint = 8;

std::size_t rangesSize(const OriginRanges& r) {
  std::size_t n = 2;  // num_origins
  for (const auto& [origin, set] : r) n += 2 + 2 + 8 * set.ranges().size();
  return n;
}
}  // namespace

std::size_t encodedSize(const Heartbeat& m) { return kFingerprint + 2 + 8 + rangesSize(m.held) + 1 + m.mac.size(); }
std::size_t encodedSize(const Chunk& m) { return kFingerprint + 2 + 2 + 8 + 1 + 2 + 4 + 2 + 2 + 2 + m.data.size() + 1 + m.mac.size(); }
std::size_t encodedSize(const Ack& m) { return kFingerprint + 2 + 2 + 8 + rangesSize(m.acked) + 1 + m.mac.size(); }

}  // namespace slide::team
