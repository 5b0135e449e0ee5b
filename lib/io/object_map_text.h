#pragma once
// Object maps as text, one object per line: `label x y z [sx sy sz [yaw]]`, as in the real robot
// maps of ../shared/data/slideslam_maps. `label` is a map label of the class table (classes.yaml
// map_labels, e.g. -2 car) or, failing that, a class id of the table; the shape is the class's.
// x y z: the object's centre (Object::position()). sx sy sz: its bounding-box extents
// (Object::extent(): cuboid length/width/height, cylinder 2r 2r length, ellipsoid 2r 2r height);
// what a line without them gets is the reader's MissingSize. yaw: radians (cuboids), 0 when absent.
// Blank lines and lines starting with '#' are skipped.
//
// readObjectMapFile also takes the CSV layout of io/ground_truth_objects.h (told apart by a
// comma in the first line that is not a comment).
#include <string>
#include <vector>

#include "objects/class_table.h"
#include "objects/object_map.h"

namespace slide::io {

// The size of an object whose line has none: zero (unknown; place recognition's maps) or the
// class's typical size (ClassInfo::typicalSize(); what evaluation and plots draw).
enum class MissingSize { Zero, ClassTypical };

struct ObjectMapText {
  ObjectMap map;                      // ids 0, 1, 2, ... in file order
  std::vector<std::string> warnings;  // skipped objects with a NaN/inf number, "file: line N: why"
};

// Throws IoError naming the file and line (unreadable file or a directory, malformed line, label
// not an integer in int range, unknown label, negative size). Objects with a NaN/inf number are
// skipped with a warning, not an error.
ObjectMapText readObjectMapText(const std::string& path, const ClassTable& classes, MissingSize missing);
// Parses text; `name` stands in for the file name in errors.
ObjectMapText parseObjectMapText(const std::string& text, const std::string& name, const ClassTable& classes,
                                 MissingSize missing);

// An object of `shape` centred at `centre` whose bounding box has the full extents `extent`
// (the inverse of Object::extent(): cuboid dims with heading `yaw`; cylinder and ellipsoid radius
// (extent.x + extent.y) / 4, length or height extent.z, upright). What both map layouts build.
Object objectFromExtent(int class_id, Shape shape, const Eigen::Vector3d& centre, const Eigen::Vector3d& extent,
                        double yaw = 0.0);
// The object of one text line: shape from the class (an ellipsoid for a class the table lacks).
Object objectFromCentre(int class_id, const Eigen::Vector3d& centre, const Eigen::Vector3d& extent,
                        const ClassTable& classes, double yaw = 0.0);
// The class a map file's label means: its map label (classes.yaml map_labels), failing that its
// class id; null when neither.
const ClassInfo* classOfMapLabel(const ClassTable& classes, int label);

// Writes `label x y z sx sy sz` per object (label: the class's first map label, else its id).
// Written whole or not at all (io/atomic_file.h); throws IoError.
void writeObjectMapText(const std::string& path, const ObjectMap& map, const ClassTable& classes);
std::string formatObjectMapText(const ObjectMap& map, const ClassTable& classes);

// A map file in either layout, for evaluation and plots: text with MissingSize::ClassTypical (an
// object with a NaN/inf number is an error here), or CSV (readObjectsCsv; default_class: the
// class of rows in a file without a class column, e.g. "x,y" pole lists; -1: such files are an
// error). Throws IoError naming file and line.
std::vector<Object> readObjectMapFile(const std::string& path, const ClassTable& classes, int default_class = -1);

}  // namespace slide::io
