#include "team/message_auth.h"

#include <openssl/evp.h>
#include <openssl/hmac.h>

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

MessageAuth::MessageAuth(std::string key) : key_(std::move(key)) {
  if (key_.empty()) throw std::invalid_argument("team key is empty");
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

Bytes MessageAuth::canonical(const Ack& m) {
  ByteWriter w;
  w.u8('A');
  w.u32(static_cast<std::uint32_t>(m.sender));
  w.u32(static_cast<std::uint32_t>(m.receiver));
  w.u64(static_cast<std::uint64_t>(m.counter));
  writeRanges(w, m.acked);
  return w.take();
}

Mac MessageAuth::macOf(const Bytes& data) const {
  unsigned char full[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  if (!HMAC(EVP_sha256(), key_.data(), static_cast<int>(key_.size()), data.data(), data.size(), full, &len) ||
      len < 16)
    throw std::runtime_error("HMAC-SHA256 failed");
  Mac mac;
  std::copy(full, full + 16, mac.begin());
  return mac;
}

bool MessageAuth::equal(const Mac& a, const Mac& b) {
  std::uint8_t diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= a[i] ^ b[i];
  return diff == 0;
}

}  // namespace slide::team
