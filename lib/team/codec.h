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

// `previous_odom`: the odometry pose of the origin's bundle seq-1 as receivers decode it, when
// known. If relative_odom equals previous_odom^-1 * odom_pose (as a tracker computes it) to
// within 0.1 mm and 1e-5 rad, it is left out as redundant and receivers recompute it from the
// two float32 poses.
Bytes encodeBundle(const Bundle& b, const Pose* previous_odom = nullptr);
// origin and seq come from the chunk header. On failure returns nullopt and sets `error`.
// A bundle whose relative odometry was left out needs `previous_odom`; without it the result
// has relative_odom = identity and *needs_previous = true.
std::optional<Bundle> decodeBundle(const Bytes& data, std::int32_t origin, std::int32_t seq, std::string* error,
                                   const Pose* previous_odom = nullptr, bool* needs_previous = nullptr);

// Maps carry what place recognition uses: class, id, position, size and yaw (confidence,
// observation counts, cylinder tilt and cuboid roll/pitch are dropped).
Bytes encodeMap(const SharedMap& m);
std::optional<SharedMap> decodeMap(const Bytes& data, std::int32_t robot, std::int32_t version, std::string* error);

}  // namespace slide::team
