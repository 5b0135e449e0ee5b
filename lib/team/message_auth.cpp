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
  w.u32(static_cast<std::uint32_t>(m.maps.size()));
  for (const auto& [origin, version] : m.maps) {
    w.u32(static_cast<std::uint32_t>(origin));
    w.u32(static_cast<std::uint32_t>(version));
  }
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

int MessageAuth::slotOf(std::int32_t origin, std::int32_t member) const {
  if (member == origin) return -1;
  int slot = 0;
  for (std::int32_t id : team_) {
    if (id == member) return slot;
    if (id != origin) ++slot;
  }
  return -1;
}

Bytes MessageAuth::bundleTags(std::int32_t seq, const Bytes& data, const std::vector<std::int32_t>& members) const {
  std::uint16_t bits = 0;
  for (std::int32_t m : members)
    if (const int slot = slotOf(robot_, m); slot >= 0) bits |= static_cast<std::uint16_t>(1u << slot);
  if (!bits) return {};
  const Bytes data_c = canonicalBundle(robot_, seq, data);
  ByteWriter w;
  w.u16(bits);
  for (std::int32_t id : team_)  // ascending, so tags follow the bits in order
    if (const int slot = slotOf(robot_, id); slot >= 0 && (bits >> slot & 1)) {
      const Mac t = tag(keys_.at(id), data_c);
      w.bytes(t.data(), t.size());
    }
  return w.take();
}

bool MessageAuth::bundleTagged(std::int32_t origin, const Bytes& block, std::int32_t member) const {
  const int slot = slotOf(origin, member);
  return slot >= 0 && block.size() >= 2 && ((block[0] | block[1] << 8) >> slot & 1);
}

bool MessageAuth::verifyBundle(std::int32_t origin, std::int32_t seq, const Bytes& data, const Bytes& block) const {
  if (block.size() < 2) return false;
  const unsigned bits = block[0] | block[1] << 8;
  if (block.size() != 2 + kTagBytes * static_cast<std::size_t>(__builtin_popcount(bits))) return false;
  if (origin == robot_) {  // every tag must be one this robot would make
    const Bytes mine = bundleTags(seq, data, team_);
    if (mine.size() < 2) return false;
    const unsigned my_bits = mine[0] | mine[1] << 8;
    if ((bits & ~my_bits) != 0 || bits == 0) return false;
    std::size_t at = 2, mine_at = 2;
    for (int slot = 0; slot < 16; ++slot) {
      if (!(my_bits >> slot & 1)) continue;
      if (bits >> slot & 1) {
        if (!equal(block.data() + at, mine.data() + mine_at, kTagBytes)) return false;
        at += kTagBytes;
      }
      mine_at += kTagBytes;
    }
    return true;
  }
  const int slot = slotOf(origin, robot_);
  if (slot < 0 || !(bits >> slot & 1) || !keys_.count(origin)) return false;
  const std::size_t index = static_cast<std::size_t>(__builtin_popcount(bits & ((1u << slot) - 1)));
  const Mac t = tag(keys_.at(origin), canonicalBundle(origin, seq, data));
  return equal(block.data() + 2 + index * kTagBytes, t.data(), kTagBytes);
}

bool MessageAuth::equal(const std::uint8_t* a, const std::uint8_t* b, std::size_t n) {
  std::uint8_t diff = 0;
  for (std::size_t i = 0; i < n; ++i) diff |= a[i] ^ b[i];
  return diff == 0;
}

}  // namespace slide::team
