#include "team/bundle_pack.h"

#include <stdexcept>

namespace slide::team {

Bytes packBundles(const std::vector<const Bytes*>& bundles, const std::vector<const Bytes*>& tags) {
  if (bundles.empty() || bundles[0]->empty()) throw std::invalid_argument("packBundles: nothing to pack");
  if (!tags.empty() && tags.size() != bundles.size()) throw std::invalid_argument("packBundles: tags do not match");
  const std::uint8_t format = (*bundles[0])[0];
  bool tagged = false;
  for (const Bytes* t : tags) tagged = tagged || (t && !t->empty());
  ByteWriter w;
  w.u8(format);
  w.varint(bundles.size() * 2 + (tagged ? 1 : 0));
  for (std::size_t i = 0; i < bundles.size(); ++i) {
    const Bytes* b = bundles[i];
    if (b->empty() || (*b)[0] != format) throw std::invalid_argument("packBundles: bundles of different formats");
    w.varint(b->size() - 1);
    w.bytes(b->data() + 1, b->size() - 1);
    if (!tagged) continue;
    const Bytes* t = tags[i];
    if (t && t->size() > kMaxPackedTags) throw std::invalid_argument("packBundles: tags too long");
    w.varint(t ? t->size() : 0);
    if (t) w.bytes(t->data(), t->size());
  }
  return w.take();
}

namespace {
std::size_t varintSize(std::uint64_t v) {
  std::size_t n = 1;
  for (; v >= 0x80; v >>= 7) ++n;
  return n;
}
}  // namespace

std::size_t packedSize(std::size_t size, std::size_t tag_bytes, bool tagged) {
  const std::size_t body = size > 0 ? size - 1 : 0;
  return varintSize(body) + body + (tagged ? varintSize(tag_bytes) + tag_bytes : 0);
}

std::optional<std::vector<PackedBundle>> unpackBundles(const Bytes& payload, std::string* error) {
  ByteReader r(payload);
  const std::uint8_t format = r.u8();
  const std::uint64_t head = r.varint(), n = head / 2;
  const bool tagged = head & 1;
  if (r.ok() && (n < 1 || n > kMaxBundlesPerPack || n > r.remaining()))
    r.fail("bundle count " + std::to_string(n) + " out of range");
  std::vector<PackedBundle> out;
  for (std::uint64_t i = 0; r.ok() && i < n; ++i) {
    const std::uint64_t len = r.varint();
    if (r.ok() && len > r.remaining()) {
      r.fail("bundle " + std::to_string(i) + " length " + std::to_string(len) + " exceeds the " +
             std::to_string(r.remaining()) + " bytes left");
      break;
    }
    if (!r.ok()) break;
    const std::uint8_t* p = payload.data() + r.position();
    PackedBundle b;
    b.data.reserve(len + 1);
    b.data.push_back(format);
    b.data.insert(b.data.end(), p, p + len);
    for (std::uint64_t k = 0; k < len; ++k) r.u8();
    const std::uint64_t tag_len = tagged ? r.varint() : 0;
    if (r.ok() && (tag_len > kMaxPackedTags || tag_len > r.remaining())) {
      r.fail("bundle " + std::to_string(i) + " tag length " + std::to_string(tag_len) + " out of range");
      break;
    }
    for (std::uint64_t k = 0; r.ok() && k < tag_len; ++k) b.tags.push_back(r.u8());
    out.push_back(std::move(b));
  }
  if (r.ok() && r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " trailing bytes after the bundles");
  if (!r.ok()) {
    if (error) *error = r.error();
    return std::nullopt;
  }
  return out;
}

}  // namespace slide::team
