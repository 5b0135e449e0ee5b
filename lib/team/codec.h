#pragma once
// Compact binary encodings of bundles and object maps for the team bus: float32 numbers,
// varints for integers, unit quaternions and axes by their smallest components, defaults
// (confidence 1, one observation, upright axis, zero sigma) as flag bits, and no field that
// the chunk header already carries (origin, sequence number). Decoding validates everything
// and reports the first problem instead of throwing.
#include <optional>
#include <string>

#include "team/bundle.h"
#include "team/byte_io.h"

namespace slide::team {

Bytes encodeBundle(const Bundle& b);
// origin and seq come from the chunk header. On failure returns nullopt and sets `error`.
std::optional<Bundle> decodeBundle(const Bytes& data, std::int32_t origin, std::int32_t seq, std::string* error);

// Maps carry what place recognition uses: class, id, position, size and yaw (confidence,
// observation counts, cylinder tilt and cuboid roll/pitch are dropped).
Bytes encodeMap(const SharedMap& m);
std::optional<SharedMap> decodeMap(const Bytes& data, std::int32_t robot, std::int32_t version, std::string* error);

}  // namespace slide::team
