#include "team/bundle_pack.h"

#include <stdexcept>

namespace slide::team {

Bytes packBundles(const std::vector<const Bytes*>& bundles) {
  if (bundles.empty() || bundles[0]->empty()) throw std::invalid_argument("packBundles: nothing to pack");
  const std::uint8_t format = (*bundles[0])[0];
  ByteWriter w;
  w.u8(format);
  w.varint(bundles.size());
  for (const Bytes* b : bundles) {
    if (b->empty() || (*b)[0] != format) throw std::invalid_argument("packBundles: bundles of different formats");
    w.varint(b->size() - 1);
    w.bytes(b->data() + 1, b->size() - 1);
  }
  return w.take();
}

std::size_t packedSize(std::size_t size) {
  const std::size_t body = size > 0 ? size - 1 : 0;
  std::size_t n = 1;
  for (std::size_t v = body; v >= 0x80; v >>= 7) ++n;
  return n + body;
}

std::optional<std::vector<Bytes>> unpackBundles(const Bytes& payload, std::string* error) {
  ByteReader r(payload);
  const std::uint8_t format = r.u8();
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
    Bytes b;
    b.reserve(len + 1);
    b.push_back(format);
    b.insert(b.end(), p, p + len);
    out.push_back(std::move(b));
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
