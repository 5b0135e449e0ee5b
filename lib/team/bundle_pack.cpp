#include "team/bundle_pack.h"

namespace slide::team {

Bytes packBundles(const std::vector<const Bytes*>& bundles) {
  ByteWriter w;
  w.varint(bundles.size());
  for (const Bytes* b : bundles) {
    w.varint(b->size());
    w.bytes(b->data(), b->size());
  }
  return w.take();
}

std::size_t packedSize(std::size_t size) {
  std::size_t n = 1;
  for (std::size_t v = size; v >= 0x80; v >>= 7) ++n;
  return n + size;
}

std::optional<std::vector<Bytes>> unpackBundles(const Bytes& payload, std::string* error) {
  ByteReader r(payload);
  const std::uint64_t n = r.varint();
  if (r.ok() && (n < 1 || n > kMaxBundlesPerPack || n > r.remaining()))
    r.fail("bundle count " + std::to_string(n) + " out of range");
  std::vector<Bytes> out;
  for (std::uint64_t i = 0; r.ok() && i < n; ++i) {
    const std::uint64_t len = r.varint();
    if (r.ok() && len > r.remaining()) {
      r.fail("bundle " + std::to_string(i) + " length " + std::to_string(len) + " exceeds the " +
             std::to_string(r.remaining()) + " bytes left");
      break;
    }
    if (!r.ok()) break;
    const std::uint8_t* p = payload.data() + r.position();
    out.emplace_back(p, p + len);
    for (std::uint64_t k = 0; k < len; ++k) r.u8();
  }
  if (r.ok() && r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " trailing bytes after the bundles");
  if (!r.ok()) {
    if (error) *error = r.error();
    return std::nullopt;
  }
  return out;
}

}  // namespace slide::team
