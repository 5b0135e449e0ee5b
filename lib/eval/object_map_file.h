#pragma once
// Object maps on disk, for evaluation and plots. Two formats, told apart by the first line:
//
// Text (as the SlideSLAM robot maps): one object per line, "label x y z [sx sy sz [yaw]]".
//   label: an object-map label of config/classes.yaml (map_labels, e.g. -2 car) or, failing
//   that, a class id of the table. x y z: the object's centre (Object::position()).
//   sx sy sz: bounding-box extents (Object::extent(): cuboid length/width/height, cylinder
//   2r 2r length, ellipsoid 2r 2r height); when absent the class's typical size is used
//   (per axis, the geometric mean of size_min and size_max). yaw: radians (cuboids).
// CSV: a header line naming columns, then one object per line. Required: class_id (or
//   class; may be absent when a default class is given), x, y. z defaults to 0. Optional: id, shape (cuboid|cylinder|ellipsoid; default the class's),
//   yaw, length width height (or size_x size_y size_z: the extents above), radius (sets
//   length = width = 2r unless those are given), axis_x axis_y axis_z (cylinders), confidence.
//   Unknown columns (semantic, vx, vy, ...) are ignored, so the simulator's ground-truth
//   objects.csv (io/ground_truth_objects.h) reads as it is. writeObjectMapCsv writes
//   "id,class_id,shape,x,y,z,yaw,length,width,height,radius,axis_x,axis_y,axis_z,confidence".
// '#' starts a comment line in both. Errors throw IoError naming file, line and field.
#include <string>
#include <vector>

#include "objects/class_table.h"
#include "objects/object.h"

namespace slide {

// default_class: the class of objects in CSV files without a class column (e.g. "x,y" pole
// lists); -1 means such files are an error.
std::vector<Object> readObjectMapFile(const std::string& path, const ClassTable& classes, int default_class = -1);
void writeObjectMapCsv(const std::string& path, const std::vector<Object>& objects);

// An object of class `class_id` (shape from the table unless given) centred at `centre`
// with bounding-box extents `extent` and yaw; used by both readers.
Object makeObject(const ClassInfo& cls, Shape shape, const Eigen::Vector3d& centre, const Eigen::Vector3d& extent,
                  double yaw);

}  // namespace slide
