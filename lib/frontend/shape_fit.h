#pragma once
// Fitting one shape model to the points of one object: cylinders (trunks, poles) from RANSAC
// circle fits on horizontal slices, cuboids (cars) from the minimum-area footprint rectangle
// with robust extents, ellipsoids (everything else) from centroid, radius and height.
// `viewpoint` is the sensor position in the points' frame: a partly seen object is completed
// away from it.
#include <optional>
#include <string>

#include "frontend/circle_fit.h"
#include "frontend/instance.h"
#include "objects/class_table.h"

namespace slide::frontend {

struct CylinderFitParams {
  double slice_height = 0.25;      // metres per horizontal slice
  int min_slice_points = 6;
  double max_height = 8.0;         // slices above the lowest point considered
  double breast_height = 1.3;      // radius taken this far above the lowest point
  double breast_window = 0.6;      // slices within +-window of breast height vote
  double min_inlier_ratio = 0.5;   // slice circle inliers / slice points
  double max_lean_deg = 20.0;      // reject clusters leaning more than this from vertical ...
  double min_axis_span = 0.75;     // ... judged over slices spanning this height (metres); below it the
                                   // centres' scatter decides the lean: the axis stands upright
  int min_points = 10;
  CircleRansacParams ransac;
};

struct CuboidFitParams {
  double low_percentile = 0.02;    // robust extents along each axis
  double high_percentile = 0.98;
  // The near edge along each axis, when a face lies there (returns within face_band of it span
  // face_min_span across the other axis), is the median of those returns, not the low
  // percentile: the percentile lies about twice the range noise in front of the face (0: off).
  double face_band = 0.1;
  double face_min_span = 0.5;
  double footprint_cell = 0.05;    // footprint thinning before the rectangle search
  double yaw_step_deg = 1.0;       // heading search step (0: minimum-area rectangle instead)
  // Visible length / class min length required: a car's 2.5 m times 0.2 is the 0.5 m of end face
  // the geometric segmenter's car clusters need (geometric.car.min_length).
  double min_visible_fraction = 0.2;
  double size_tolerance = 1.1;     // fitted extents may exceed the class maximum by this factor
  // A horizontal extent shorter than this fraction of the class's typical one is taken as partly
  // hidden and grows to the typical extent away from the sensor (0: only below the class minimum).
  double complete_fraction = 0.9;
  // ... unless placed elsewhere along its axis it covers at least this many fewer of the cells
  // seen empty (free_space; 0: never moved), tried in steps of free_step metres.
  int free_cells_to_move = 2;
  double free_step = 0.1;
  // A box whose length went unseen takes its other reading when that covers at least this many
  // fewer cells seen empty (0: off).
  int free_cells_to_swap = 2;
  int min_points = 30;
};

struct EllipsoidFitParams {
  double radius_percentile = 0.9;  // horizontal distance from the centroid
  double low_percentile = 0.02;
  double high_percentile = 0.98;
  int min_points = 10;
  // Completion of a partly seen body (fitEllipsoid): horizontal slices of this height ...
  double slice_height = 0.1;       // metres
  int min_slice_points = 10;       // ... with at least this many points ...
  double slice_percentile = 0.01;  // ... whose bearings from the viewpoint span this and 1 - this quantile;
  double widest_fraction = 0.9;    // the slices at least this fraction as wide (sine of half the span) as the widest vote
  double max_sin_half_angle = 0.9; // a wider view is from within the object: box centre
};

struct FitParams {
  CylinderFitParams cylinder;
  CuboidFitParams cuboid;
  EllipsoidFitParams ellipsoid;
};

// Each returns nullopt (and a reason in *why) when the points do not support the model.
std::optional<Cylinder> fitCylinder(const Cloud& pts, const CylinderFitParams& p, const Eigen::Vector3d& viewpoint,
                                    std::string* why = nullptr);
// size_min/size_max: the class's plausible extents (length, width, height); size_typical: the
// extents a partly seen box is completed to (away from the viewpoint) along the axes seen
// shorter. The box's x is its length: a lone visible face (little depth) that fits the class
// width but not its length is taken as an end (a car's front or rear) and the length runs
// along the other axis. When no visible face is as long as the class's shortest length, which
// axis holds the length is a guess: *other_reading (when given) then gets the box with the
// length along the other axis (if that fits the class), and stays empty otherwise.
// free_space (when given): cells seen empty (FreeSpace, same frame as pts): a completed extent is
// placed where it covers fewer of them than away from the viewpoint, when it can
// (CuboidFitParams::free_cells_to_move).
std::optional<Cuboid> fitCuboid(const Cloud& pts, const CuboidFitParams& p, const Eigen::Vector3d& viewpoint,
                                const Eigen::Vector3d& size_min, const Eigen::Vector3d& size_max,
                                const Eigen::Vector3d& size_typical, std::string* why = nullptr,
                                std::optional<Cuboid>* other_reading = nullptr, const Cloud* free_space = nullptr);
// The centroid is completed away from the viewpoint: each horizontal slice is taken as a circle
// seen from the viewpoint (its nearest range and angular width give the centre's distance), so a
// partly seen object is as deep as it is wide across the line of sight.
// min_half_depth (metres): the centre lies at least this far behind the nearest points (the
// class's typical half-depth: a view cut by the image border or by an occluder shows less than
// the object's width).
std::optional<Ellipsoid> fitEllipsoid(const Cloud& pts, const EllipsoidFitParams& p, const Eigen::Vector3d& viewpoint,
                                      double min_half_depth = 0.0, std::string* why = nullptr);

// The model of the object's class (ClassTable shape), with class size gates applied.
// *other_reading (when given): a box's other reading, as fitCuboid gives it (passing the same gates).
// free_space: cells seen empty near the object (boxes only; fitCuboid).
std::optional<Object> fitObject(const Cloud& pts, int class_id, const ClassTable& classes, const FitParams& p,
                                const Eigen::Vector3d& viewpoint, std::string* why = nullptr,
                                std::optional<Object>* other_reading = nullptr, const Cloud* free_space = nullptr);

}  // namespace slide::frontend
