#pragma once
// Compact binary encodings (format 3) of bundles and object maps for the team bus. Integers are
// varints, defaults are flag bits, and nothing the chunk header carries (origin, sequence
// number) is repeated. Decoding validates everything and reports the first problem (naming
// the field) instead of throwing.
//
// Quantisation (value = integer * unit; the error is at most half a unit):
//   relative odometry        translation 1 mm per axis, rotation vector 1e-4 rad per component
//   chained odometry pose    within 0.9 mm and 1e-4 rad of the origin's pose (no drift: each
//                            step is quantised against the previous pose as receivers decode it)
//   object positions         1 cm per axis in bundles (body frame), 5 cm in maps (map frame)
//   cuboid yaw               1/65536 turn (1e-4 rad) in bundles, 1/256 turn (0.7 deg) in maps;
//                            roll and pitch 1e-3 rad
//   cylinder axis            x and y components 1e-3 (tilt error < 1e-3 rad)
//   cylinder radius          1 cm (0..2.55 m)     cylinder length   10 cm (0..25.5 m)
//   cuboid dimensions        5 cm (0..12.75 m)    ellipsoid radius  1 cm (0..2.55 m),
//                                                 ellipsoid height  5 cm (0..12.75 m)
//   confidence               1/255 (0..1)
//   a box's other reading    (bundles) its centre 5 cm per axis from the box's (within 100 m),
//                            its dimensions as above; its rotation is the box's turned a
//                            quarter about its own vertical
//   odometry sigma           1/16 octave (relative error <= 2.2%; 1.7e-4..10.9)
// All of these are far below the measurement noise (several cm, degrees). A value outside its
// range is never clamped: the object carries that group of fields as float32 under a flag
// (positions beyond +-327 m in a body frame, sizes beyond the ranges above, confidence
// outside 0..1, sigma outside its range). utime, ids, classes and observation counts are exact.
#include <array>
#include <optional>
#include <string>

#include "objects/keypose_bundle.h"
#include "team/byte_io.h"
#include "team/shared_map.h"

namespace slide::team {

// What a bundle may take from its origin's bundle seq-1 (as receivers decode it): the pose,
// utime and sigma it is chained to, and the motion and time steps that predict its own.
struct BundleContext {
  std::int64_t utime = 0;
  Pose odom_pose = Pose::Identity();
  Vector6d odom_sigma = Vector6d::Zero();
  Pose relative_odom = Pose::Identity();  // that bundle's step
  std::int64_t dt = 0;                    // its utime step (0: not chained)
  // `chained_to`: the context b's encoding is chained to (null when self-contained, see
  // chainedBundle()). Sender and receivers build contexts alike, from decoded bundles.
  static BundleContext of(const KeyPoseBundle& b, const BundleContext* chained_to);
};

// A bundle after a gap (KeyPoseBundle::gap > 0) is self-contained and writes the gap's length.
// `previous`: the decoded context of the origin's bundle seq-1, when known. If the bundle's
// relative odometry agrees with previous->odom_pose^-1 * odom_pose (as a tracker computes it)
// to within 2 mm and 2e-4 rad, the bundle is chained: the odometry pose derived from the
// previous one and the quantised step, sigma left out when it quantises as the previous one,
// and utime and step written as their differences from the previous bundle's (a robot moving
// steadily repeats its last step, so the differences are small).
//
// Full: everything the robot's own stack has (its journal). Team: as peers get it, without the
// tracks' observation counts (nothing downstream of peer sync reads them for a peer's bundle;
// they decode as 1). The detector confidence stays: the optimizer weighs class votes by it.
enum class BundleDetail { Full, Team };
Bytes encodeBundle(const KeyPoseBundle& b, const BundleContext* previous = nullptr, BundleDetail detail = BundleDetail::Full);
// origin and seq come from the chunk header. On failure returns nullopt and sets `error`.
// A chained bundle needs `previous`; without it the result has only its objects and flags
// right (utime, odometry and sigma are not) and *needs_previous = true.
std::optional<KeyPoseBundle> decodeBundle(const Bytes& data, std::int32_t origin, std::int32_t seq, std::string* error,
                                   const BundleContext* previous = nullptr, bool* needs_previous = nullptr);

// True when the encoding takes utime and pose from bundle seq-1 (reads the flags only).
bool chainedBundle(const Bytes& data);

// Maps carry what place recognition uses: class, id, position, size and yaw (confidence,
// observation counts, cylinder tilt and cuboid roll/pitch are dropped). Positions travel as
// centimetre differences from the previous object's.
Bytes encodeMap(const SharedMap& m);
std::optional<SharedMap> decodeMap(const Bytes& data, std::int32_t robot, std::int32_t version, std::string* error);

// A map's changes against an earlier version of it that the receivers hold (`base`): the ids
// of objects gone and the objects new or changed (written as in maps), with the new version's
// utime and frame. map_sharing.h decides what changed.
struct MapDelta {
  std::int32_t base = 0;
  std::int64_t utime = 0;
  std::int32_t frame_robot = 0;
  std::vector<std::int64_t> removed;
  std::vector<Object> changed;
};
Bytes encodeMapDelta(const MapDelta& d);
std::optional<MapDelta> decodeMapDelta(const Bytes& data, std::string* error);

}  // namespace slide::team
