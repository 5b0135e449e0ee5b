#pragma once
// The payload of a bundle chunk: the encodings (codec.h) of one or more consecutive bundles of
// one origin, the first numbered by the chunk's seq. Several small bundles share one chunk and
// so one set of per-message overheads (LCM framing, header, MAC). Every encoding starts with
// its format byte, and one pack holds one format, written once. Layout: the format byte, a
// varint count, then per bundle a varint length and the bytes after its format byte.
#include <optional>
#include <string>
#include <vector>

#include "team/byte_io.h"

namespace slide::team {

constexpr std::size_t kMaxBundlesPerPack = 4096;

// Throws std::invalid_argument when the bundles are empty or differ in their first byte.
Bytes packBundles(const std::vector<const Bytes*>& bundles);
// Bytes a bundle of `size` bytes adds to a pack (after the first byte, which is shared).
std::size_t packedSize(std::size_t size);
// The bundles, or nullopt with `error` naming the problem (count, a length, trailing bytes).
std::optional<std::vector<Bytes>> unpackBundles(const Bytes& payload, std::string* error);

}  // namespace slide::team
