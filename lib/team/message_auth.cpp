#include "team/message_auth.h"

#include <openssl/evp.h>
#include <openssl/hmac.h>

#include <algorithm>
#include <stdexcept>

namespace slide::team {
namespace {

void writeRanges(ByteWriter& w, const OriginRanges& r) {
  w.u32(static_cast<std::uint32_t>(r.size()));
  for (const auto& [origin, set] : r) {
    w.u32(static_cast<std::uint32_t>(origin));
    const auto ranges = set.ranges();
    w.u32(static_cast<std::uint32_t>(ranges.size()));
    for (const auto& x : ranges) {
      w.u32(static_cast<std::uint32_t>(x.first));
      w.u32(static_cast<std::uint32_t>(x.last));
    }
  }
}

}  // namespace

MessageAuth::MessageAuth(std::int32_t robot, std::vector<std::int32_t> team, PairKeys keys)
    : robot_(robot), team_(std::move(team)), keys_(std::move(keys)) {
  std::sort(team_.begin(), team_.end());
  team_.erase(std::unique(team_.begin(), team_.end()), team_.end());
  if (team_.size() > kMaxTeam)
    throw std::invalid_argument("team of " + std::to_string(team_.size()) + " robots: at most " +
                                std::to_string(kMaxTeam) + " (one tag per member in each message)");
  for (std::int32_t id : team_)
    if (id != robot_ && (!keys_.count(id) || keys_.at(id).empty()))
      throw std::invalid_argument("no team key for the pair of robots " + std::to_string(robot_) + " and " +
                                  std::to_string(id) + " (team key file)");
}

Bytes MessageAuth::canonical(const Heartbeat& m) {
  ByteWriter w;
  w.u8('H');
  w.u32(static_cast<std::uint32_t>(m.sender));
  w.u64(static_cast<std::uint64_t>(m.counter));
  writeRanges(w, m.held);
  return w.take();
}

Bytes MessageAuth::canonical(const Chunk& m) {
  ByteWriter w;
  w.u8('C');
  w.u32(static_cast<std::uint32_t>(m.sender));
  w.u32(static_cast<std::uint32_t>(m.receiver));
  w.u64(static_cast<std::uint64_t>(m.counter));
  w.u8(static_cast<std::uint8_t>(m.kind));
  w.u32(static_cast<std::uint32_t>(m.origin));
  w.u32(static_cast<std::uint32_t>(m.seq));
  w.u32(static_cast<std::uint16_t>(m.chunk_index));
  w.u32(static_cast<std::uint16_t>(m.num_chunks));
  w.u32(static_cast<std::uint32_t>(m.data.size()));
  w.bytes(m.data.data(), m.data.size());
  return w.take();
}

Bytes MessageAuth::canonicalBundle(std::int32_t origin, std::int32_t seq, const Bytes& data) {
  ByteWriter w;
  w.u8('B');
  w.u32(static_cast<std::uint32_t>(origin));
  w.u32(static_cast<std::uint32_t>(seq));
  w.u32(static_cast<std::uint32_t>(data.size()));
  w.bytes(data.data(), data.size());
  return w.take();
}

Bytes MessageAuth::canonical(const Ack& m) {
  ByteWriter w;
  w.u8('A');
  w.u32(static_cast<std::uint32_t>(m.sender));
  w.u32(static_cast<std::uint32_t>(m.receiver));
  w.u64(static_cast<std::uint64_t>(m.counter));
  writeRanges(w, m.acked);
  return w.take();
}

Mac MessageAuth::tag(const std::string& key, const Bytes& data) const {
  unsigned char full[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  if (!HMAC(EVP_sha256(), key.data(), static_cast<int>(key.size()), data.data(), data.size(), full, &len) ||
      len < kTagBytes)
    throw std::runtime_error("HMAC-SHA256 failed");
  return Mac(full, full + kTagBytes);
}

Mac MessageAuth::tags(const Bytes& data) const {
  Mac out;
  out.reserve(tagBytes(team_.size()));
  for (std::int32_t id : team_) {
    if (id == robot_) continue;
    const Mac t = tag(keys_.at(id), data);
    out.insert(out.end(), t.begin(), t.end());
  }
  return out;
}

bool MessageAuth::check(std::int32_t sender, const Bytes& data, const Mac& mac) const {
  if (sender == robot_ || !keys_.count(sender) || mac.size() != tagBytes(team_.size())) return false;
  // This robot's slot: its rank among the members other than the sender.
  std::size_t slot = 0;
  bool sender_in_team = false;
  for (std::int32_t id : team_) {
    if (id == sender) sender_in_team = true;
    else if (id < robot_) ++slot;
  }
  if (!sender_in_team) return false;
  const Mac t = tag(keys_.at(sender), data);
  return equal(mac.data() + slot * kTagBytes, t.data(), kTagBytes);
}

bool MessageAuth::verifyBundle(std::int32_t origin, std::int32_t seq, const Bytes& data, const Mac& tags) const {
  if (origin != robot_) return check(origin, canonicalBundle(origin, seq, data), tags);
  const Mac mine = bundleTags(seq, data);
  return !mine.empty() && tags.size() == mine.size() && equal(tags.data(), mine.data(), mine.size());
}

bool MessageAuth::equal(const std::uint8_t* a, const std::uint8_t* b, std::size_t n) {
  std::uint8_t diff = 0;
  for (std::size_t i = 0; i < n; ++i) diff |= a[i] ^ b[i];
  return diff == 0;
}

}  // namespace slide::team
