#pragma once
// Analytic ray intersections with the simulator's primitive shapes. Rays are (o, d) with d a
// unit vector; each returns the smallest t > t_min where the ray enters the shape, or +inf.
#include <Eigen/Core>

namespace slide::simulator {

// Finite cylinder with end caps: bottom centre `root`, unit `axis`, `radius`, `length`.
double intersectRayCylinder(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& root,
                            const Eigen::Vector3d& axis, double radius, double length, double t_min = 0);
// Oriented box: `R_box_world` rotates world vectors into the box frame, `centre` in the world,
// `half` the half extents.
double intersectRayBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Matrix3d& R_box_world,
                       const Eigen::Vector3d& centre, const Eigen::Vector3d& half, double t_min = 0);
// Axis-aligned ellipsoid with semi-axes `semi` around `centre`.
double intersectRayEllipsoid(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& centre,
                             const Eigen::Vector3d& semi, double t_min = 0);

}  // namespace slide::simulator
