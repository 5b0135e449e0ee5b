#pragma once
// The payload of a bundle chunk: the encodings (codec.h) of one or more consecutive bundles of
// one origin, the first numbered by the chunk's seq. Several small bundles share one chunk and
// so one set of per-message overheads (LCM framing, header, MAC). Layout: varint count, then
// per bundle a varint length and the bytes.
#include <optional>
#include <string>
#include <vector>

#include "team/byte_io.h"

namespace slide::team {

constexpr std::size_t kMaxBundlesPerPack = 4096;

Bytes packBundles(const std::vector<const Bytes*>& bundles);
// Bytes a bundle of `size` bytes adds to a pack.
std::size_t packedSize(std::size_t size);
// The bundles, or nullopt with `error` naming the problem (count, a length, trailing bytes).
std::optional<std::vector<Bytes>> unpackBundles(const Bytes& payload, std::string* error);

}  // namespace slide::team
