#pragma once
// Object lists inside the format-2 bundle and map encodings (codec.h states the quantisation).
// Per object: a tag byte (shape, flags), the id as a difference from the previous object's,
// the class unless it repeats, then the quantised fields. In a bundle (body frame) positions
// are absolute; in a map they are differences from the previous object's, and only what place
// recognition uses is kept.
#include <vector>

#include "objects/object.h"
#include "team/byte_io.h"

namespace slide::team {

enum class ObjectListKind { Bundle, Map };

void writeObjects(ByteWriter& w, const std::vector<Object>& objects, ObjectListKind kind);
// Replaces *out; on failure marks `r` failed (naming the object and field) and returns false.
bool readObjects(ByteReader& r, std::vector<Object>* out, ObjectListKind kind);

}  // namespace slide::team
