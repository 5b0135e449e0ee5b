#pragma once
// The payload of a bundle chunk: the encodings (codec.h) of one or more consecutive bundles of
// one origin, the first numbered by the chunk's seq. Several small bundles share one chunk and
// so one set of per-message overheads (LCM framing, header, MAC). Every encoding starts with
// its format byte, and one pack holds one format, written once. A bundle may travel with its
// origin's tag block (message_auth.h), so a relayed bundle is authenticated by its origin, not
// by the relay. Layout: the format byte, a varint of count * 2 + (1 when tags follow), then
// per bundle a varint length and the bytes after its format byte, and when tags follow, a
// varint tag length and the tag block. A pack without tags costs nothing more.
#include <optional>
#include <string>
#include <vector>

#include "team/byte_io.h"

namespace slide::team {

constexpr std::size_t kMaxBundlesPerPack = 4096;
constexpr std::size_t kMaxPackedTags = 255;  // above the 120 bytes of tags of the largest team

struct PackedBundle {
  Bytes data;  // the bundle's encoding (codec.h)
  Bytes tags;  // its origin's tags (empty: none)
};

// `tags`: one entry per bundle (null: none), or empty for none at all. Throws
// std::invalid_argument when the bundles are empty or differ in their first byte, or tags are
// longer than kMaxPackedTags.
Bytes packBundles(const std::vector<const Bytes*>& bundles, const std::vector<const Bytes*>& tags = {});
// Bytes a bundle of `size` bytes adds to a pack (after the first byte, which is shared), with
// `tag_bytes` of tags in a pack with tags (`tagged`).
std::size_t packedSize(std::size_t size, std::size_t tag_bytes = 0, bool tagged = false);
// The bundles, or nullopt with `error` naming the problem (count, a length, trailing bytes).
std::optional<std::vector<PackedBundle>> unpackBundles(const Bytes& payload, std::string* error);

}  // namespace slide::team
