#pragma once
// Object lists as CSV: the ground-truth objects of a simulated world (objects.csv beside the
// robot folders), and object maps in the same layout or any part of it (readObjectsCsv).
//
// objects.csv: one header line, then one object per line, comma-separated:
//   id,class_id,shape,x,y,z,yaw,length,width,height,radius,axis_x,axis_y,axis_z,semantic,vx,vy
// - id: instance id of the object's points in labels/*.label and instance masks
//   (= object index + 1, so id 1 is the first object of the file);
// - class_id: config/classes.yaml (car 10 cuboid, trunk 71 / pole 80 cylinder,
//   chair 1 / table 2 / monitor 3 / other 0 ellipsoid); shape: cuboid|cylinder|ellipsoid;
// - x,y,z: centre in the world frame (cuboid centre, cylinder axis midpoint, ellipsoid
//   centroid); yaw: cuboid heading (radians, x axis along the length), 0 for the others;
// - length,width,height: cuboid extents; cylinder: 2r,2r,axis length; ellipsoid: 2r,2r,height;
// - radius: cylinder/ellipsoid horizontal radius (0 for cuboids);
// - axis_x..z: unit cylinder axis (leaning trunks), 0,0,1 for the others;
// - semantic: SemanticKITTI-style label of its points (sim/semantic_labels.h);
// - vx,vy: velocity in m/s (moving cars; 0 for static objects). A moving object's centre at
//   time t (seconds since the start of the simulation) is (x + vx t, y + vy t, z).
#include <cstdint>
#include <string>
#include <vector>

#include "objects/object.h"

namespace slide {
class ClassTable;
}  // namespace slide

namespace slide::io {

struct GroundTruthObject {
  Object object;                                      // object.id = instance id (index + 1)
  uint16_t semantic = 0;                              // per-point label of its points
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  // m/s in the world frame
  bool moving() const { return velocity.squaredNorm() > 0; }
  // The object at time t (seconds): translated by velocity * t.
  Object at(double t) const;
};

void writeGroundTruthObjects(const std::string& path, const std::vector<GroundTruthObject>& objects);
// readObjectsCsv without a class table, with semantic, vx and vy required.
std::vector<GroundTruthObject> readGroundTruthObjects(const std::string& path);

// Objects of a CSV file: a header line naming columns (blank and '#' lines before it and among the
// rows are skipped), then one object per line; columns in any order, unknown ones ignored.
//   class_id (or class): a map label or class id of `classes` (a class id as it is when
//     `classes` is null); may be absent when default_class >= 0, which every row then gets;
//   x, y (required), z (default 0); id (default: the row's index);
//   shape: cuboid|cylinder|ellipsoid (default the class's; required when `classes` is null);
//   yaw (radians, cuboids); length width height, or size_x size_y size_z: the extents of
//     Object::extent() (default the class's typical size; zero when `classes` is null);
//   radius: cylinders and ellipsoids, sets length = width = 2 radius (over those columns);
//   axis_x axis_y axis_z: a cylinder's axis (normalised; upright when absent); confidence.
// `extra`: further columns, required, whose numbers go to *extra_values (one row per object).
// Throws IoError naming the file, line and column (missing file or column, a cell that is not a
// finite number, an unknown label or shape, a negative size, a zero cylinder axis).
std::vector<Object> readObjectsCsv(const std::string& path, const ClassTable* classes, int default_class = -1,
                                   const std::vector<std::string>& extra = {},
                                   std::vector<std::vector<double>>* extra_values = nullptr);

}  // namespace slide::io
