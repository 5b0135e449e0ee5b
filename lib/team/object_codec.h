#pragma once
// Object lists inside the bundle and map encodings (codec.h states the quantisation). Per
// object: a tag byte (shape, flags), the id as a difference from the previous object's, the
// class unless it repeats, then the quantised fields. In a bundle (body frame) positions are
// absolute; in a map they are differences from the previous object's, and only what place
// recognition uses is kept. A bundle as the team bus carries it leaves out the track's
// observation count (no peer uses it; it decodes as 1) and keeps the detector confidence: a
// peer's optimizer weighs class votes by it (a label-free "other" yields to a named class).
// Bundles keep a box's other reading (Object::other_reading; the front-end's is the box turned a
// quarter about its own vertical, and only such a reading travels): a peer's optimizer, like the
// robot's own, keeps the reading its landmark agrees with.
#include <vector>

#include "objects/object.h"
#include "team/byte_io.h"

namespace slide::team {

enum class ObjectListKind { Bundle, TeamBundle, Map };

void writeObjects(ByteWriter& w, const std::vector<Object>& objects, ObjectListKind kind);
// Replaces *out; on failure marks `r` failed (naming the object and field) and returns false.
bool readObjects(ByteReader& r, std::vector<Object>* out, ObjectListKind kind);

}  // namespace slide::team
