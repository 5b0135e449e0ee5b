#pragma once
// Object maps as text, one object per line: `label x y z [sx sy sz]`, as in the real robot maps
// of ../shared/data/slideslam_maps. `label` is a map label of the class table (classes.yaml
// map_labels) or, failing that, a class id of the table; x y z is the object's centre; the
// optional sx sy sz are its bounding-box extents (Object::extent()), zero when absent
// (size unknown). Blank lines and lines starting with '#' are skipped.
#include <string>
#include <vector>

#include "objects/class_table.h"
#include "objects/object_map.h"

namespace slide {

struct ObjectMapText {
  ObjectMap map;
  std::vector<std::string> warnings;  // e.g. skipped non-finite objects, "file:line: why"
};

// Throws std::runtime_error naming the file and line (unreadable file or a directory, malformed
// line, label not an integer in int range, unknown label). Objects with a NaN/inf number are skipped with a warning, not an error.
ObjectMapText readObjectMapText(const std::string& path, const ClassTable& classes);
// Parses text; `name` stands in for the file name in errors.
ObjectMapText parseObjectMapText(const std::string& text, const std::string& name, const ClassTable& classes);

// The object built for one line: shape from the class, centre p, extents (zero: unknown).
Object objectFromCentre(int class_id, const Eigen::Vector3d& p, const Eigen::Vector3d& extent,
                        const ClassTable& classes);

// Writes `label x y z sx sy sz` per object (label: the class's first map label, else its id).
// Throws std::runtime_error naming the file when it cannot be written.
// Written whole or not at all (io/atomic_file.h); throws IoError.
void writeObjectMapText(const std::string& path, const ObjectMap& map, const ClassTable& classes);
std::string formatObjectMapText(const ObjectMap& map, const ClassTable& classes);

}  // namespace slide
