#pragma once
// Ground-truth object list of a simulated world, as CSV (objects.csv beside the robot folders).
//
// File layout: one header line, then one object per line, comma-separated:
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

struct GroundTruthObject {
  Object object;                                      // object.id = instance id (index + 1)
  uint16_t semantic = 0;                              // per-point label of its points
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  // m/s in the world frame
  bool moving() const { return velocity.squaredNorm() > 0; }
  // The object at time t (seconds): translated by velocity * t.
  Object at(double t) const;
};

void writeGroundTruthObjects(const std::string& path, const std::vector<GroundTruthObject>& objects);
// Throws IoError naming the file and line for a missing file, bad header or unparsable line.
std::vector<GroundTruthObject> readGroundTruthObjects(const std::string& path);

}  // namespace slide
