#pragma once
// Segmentation without a trained model: ground removal, then
//  1. columns: stacks of small isolated cross-sections in height slices above ground
//     (trunks and poles; a trunk when a canopy spreads above it or it is thick; see
//     column_detection.h),
//  2. cars: clusters of the remaining points below a height cap whose footprint and height
//     fit a car and whose roof is open (a wall's lower part goes on above the cap), leaving out
//     stacks that reach the top of the view and what stands beside them (ViewCutParams),
//  3. other: clusters of what is left whose extents fit the "other" class (no taller than
//     furniture: other_max_height), that stand low,
//     whose surfaces are solid (not foliage), that are seen whole (not cut off by a nearer
//     occluder beside them; see occlusion.h) and that are no upright column.
#include "frontend/column_detection.h"
#include "frontend/free_space.h"
#include "frontend/grid_clustering.h"
#include "frontend/ground_removal.h"
#include "frontend/occlusion.h"
#include "frontend/view_notch.h"
#include "frontend/segmenter.h"
#include "objects/class_table.h"

namespace slide::frontend {

struct CarParams {
  double height_cap = 2.6;       // points above this height are left out of car clusters
  double cell = 0.3;
  int min_points = 40;
  // Beyond near_range metres (nearest return) a car gives fewer returns, down to min_points_far
  // (min_points x (near_range / range)^2, at least min_points_far; min_points_far >= min_points: off).
  int min_points_far = 40;
  double near_range = 25.0;
  // 95th percentile of height above ground. Cars stand 1.4 m or taller: the 95th percentile of
  // their sides reaches 1.2 m even when the roof is out of sight (a table with monitors on it,
  // 1.15 m, does not; at 1.0 indoor table groups were cars).
  double min_top = 1.2, max_top = 2.3;
  double max_bottom = 0.8;       // 5th percentile of height above ground
  // Clusters whose nearest return lies farther (horizontally) are no cars (0: off): a few beams
  // of a far car cannot be told from the top of a facade seen over nearer objects, whose lowest
  // returns make its ground (the tracker meets a real car again nearer).
  double max_range = 40.0;
  double min_length = 1.2, max_length = 6.5;
  double max_width = 2.8;
  // A cluster longer or wider than that is re-clustered on cells half as large, down to this
  // cell (cars parked a few decimetres apart join at `cell`); cell or more: no splitting.
  double min_split_cell = 0.15;
  double max_split_length = 13.0;  // ... when no side of its bounding box is longer (two cars back to back)
  NotchSplitParams notch;          // a cluster with a notch in its view is split there (cars parked nose out)
  // A car-sized cluster that falls apart on cells this large into two or more parts of at least
  // min_points is split into them (an end face joined on `cell` to a stripe of the next car's
  // side seen through the gap; 0: off). Clustered on x, y: the gap between cars is a vertical slot.
  double gap_cell = 0.15;
  double gap_angle_deg = 0.0;  // ... or, where wider, this angle at the cluster's range (a LiDAR's columns spread apart with range)
  int gap_min_points = 40;
  // Median |r(i-1) - 2 r(i) + r(i+1)| of ranges along the scan order within the cluster:
  // car bodies are smooth (~2 cm), vegetation is not (~8 cm); simulated 2 cm range noise gives ~4 cm. 0 disables; clusters with
  // fewer than 10 consecutive triplets (unordered scans) skip the test when they hold min_points returns, and are no car
  // when they hold fewer (min_points_far is for faces that show their smoothness) ...
  double max_roughness = 0.07;
  // ... unless their returns lie on the edges of their top-view rectangle (median distance to
  // the nearest edge, edgeSpread, at most this): a far car's faces seen by a few beams, where a
  // patch of ground or foliage fills its rectangle (0: no such exception).
  double max_edge_spread = 0.0;
  // A car's roof is open: at most this share of the cluster's cells (cell x cell metres) may
  // hold returns from height_cap to height_cap + cover_height (a wall, a hedge under it or a
  // building's lower storey goes on above the cap; a car ends below it). 1 disables.
  double max_covered = 0.3;
  double cover_height = 1.0;
  // A car stands on the ground: a cluster whose bottom is hidden (on more than max_hidden_bottom
  // of its azimuth steps a line of sight at most hidden_below metres under its lowest return
  // ends hidden_margin metres or more nearer: its lowest returns above ground, within the ground
  // threshold, are no part of it) and whose ground estimate lies more than max_ground_rise above
  // that of what hides it floats: a wall's piece seen over furniture, its own bottom edge taken
  // for the ground there. 1 disables.
  double max_hidden_bottom = 1.0;
  double hidden_below = 0.5;
  double hidden_margin = 0.5;
  double max_ground_rise = 0.3;
  // A car stands on the ground seen around it: where the ground's own returns were seen nearest
  // to the cluster (SeenGround cells 1 to seen_ground_search metres from its edge), its ground
  // estimate lies at most seen_ground_rise + seen_ground_slope x that distance above them. A crown's or a
  // roof's underside far off, where no ground return falls within the ground window, makes its
  // own ground (0: off).
  double seen_ground_search = 0.0;
  double seen_ground_rise = 0.5;
  double seen_ground_slope = 0.15;
};

// The top of the view: where the scan's top beam hits something in most directions (walls, a
// ceiling, crowns all around; ScanLines::viewTop), a stack of returns that reaches it goes on
// above what the sensor sees. Its height is unknown, so the points under such a return are no
// car and no "other": indoors the lower part of a wall beside the robot fits a car's height and
// footprint, and furniture standing near it joins it.
struct ViewCutParams {
  double tolerance_deg = 0.2;    // a return this close to the top beam's elevation reaches it (0: off)
  double min_share = 0.1;        // share of azimuth bins (0.25 deg) the top beam must hit
  double range_tolerance = 0.1;  // metres: a return in the azimuth bin of such a return or the next, this close in range, is under it
  // The top beam may leave from up to this far above or below the sensor frame's origin
  // (ScanLines::viewTop; a multi-laser head's emitters sit above it).
  double max_origin_height = 0.5;
  // A car cluster more than this share of whose returns stand beside such a return (its azimuth
  // bin or the next, within beside_range metres of range) is the lower part of a stack cut off
  // by the view: no car (1: off).
  double max_beside_share = 1.0;
  double beside_range = 0.3;
};

struct GeometricSegmenterParams {
  GroundParams ground;
  double max_range = 60.0;       // metres, horizontal
  ColumnParams column;
  ViewCutParams view_cut;
  CarParams car;
  // Cells a car instance's box may not be completed over: where lines of sight near it passed
  // through a car body's height band (Instance::free_space; cell 0: none).
  FreeSpaceParams free_space;
  GridClusterParams other_cluster{0.3, false, 30};
  // An "other" cluster whose footprint is longer than this is clustered again on cells half as
  // large (a chair pushed to a table stands a decimetre from it), each part of at least
  // other_split_min_points becoming a cluster of its own when there are two or more; 0: off.
  double other_split_length = 0.0;
  int other_split_min_points = 120;
  bool emit_other = true;        // emit "other" instances for remaining compact clusters ...
  // ... whose range roughness (as CarParams::max_roughness) is at most this: solid things (bins,
  // boxes, furniture), not foliage (bushes, low crowns; real SemanticKITTI vegetation: median
  // 0.08 m, solid surfaces 0.02 m). 0 disables.
  double other_max_roughness = 0.07;
  // Both roughness limits (this and CarParams::max_roughness) are at most this many times the
  // scan's own noise floor: the 25th percentile of the second differences over all returns
  // above the ground (walls, car bodies and trunks set it; foliage lies above it). The limits
  // were set at the simulator's 2 cm range noise, whose floor is 0.023-0.032 m; a real
  // HDL-64E's is 0.015-0.017 m, its car bodies 0.012-0.037 m and its bushes 0.049-0.058 m.
  // 0 disables. They are never lowered below roughness_cap_min: geometry alone (edges, sparse
  // far returns) makes a smooth face that rough on a sensor with little or no noise.
  double roughness_floor_factor = 0.0;
  double roughness_cap_min = 0.04;
  // ... and that stand on the ground or on furniture (2nd percentile of height above ground
  // at most this; a crown's lower edge floats metres up).
  double other_max_bottom = 1.0;
  // ... and that are seen whole: at most this share of their beams end at a nearer occluder
  // (a car's end seen past the car in front of it is no small object). 1 disables. The rule
  // judges only clusters that could be the seen part of something larger: as tall as a car
  // (the car class's size_min height; a hidden car end shows the car's whole height) or
  // thinner than other_face_max_width across their footprint (a strip of wall or fence seen
  // between things in front of it is as thin as the range noise). Lower, thicker ones (a table
  // behind its chairs, a chair behind another) stand whole behind what hides their edge.
  double other_max_occluded = 0.5;
  double other_face_max_width = 0.0;  // 0: every cluster is judged
  // ... and that end where they seem to: at most this share of their azimuth bins show the
  // face going on past their top or bottom (the next beam up or down at their range,
  // ScanLines::continuedFraction): a wall far off, its beams farther apart than the fine
  // clustering cells, falls into bands of furniture height. 1 disables.
  double other_max_continued = 1.0;
  // ... and that are no upright column: a cluster as tall as a column must be (column.min_top)
  // whose footprint is no longer than a column's cross-section (column.max_diameter) is a
  // trunk or pole the column step turned down (not isolated, a bush at its foot). false: off.
  bool other_not_column = true;
  // ... and that are no upright stub: at most this many times as tall (2nd to 98th percentile)
  // as their footprint is long. A trunk whose crown hides its top, or a pole cut off by the
  // view, is a column too short for the column step; furniture, bins and boxes are squat.
  // 0: off.
  double other_max_slenderness = 0.0;
  // ... and that are no taller than this (metres, 2nd to 98th percentile of height; 0: the
  // "other" class's size_max): a wall's piece between two doors stands from floor to
  // ceiling; furniture, bins and boxes stand lower.
  double other_max_height = 0.0;
  // Confidence of an "other" instance: without labels "other" names no class, it only says
  // "an object of none of the classes told by shape". Kept low, its votes yield to a named
  // observation of the same object (a peer's detector, once merged). 1: a class like any other.
  double other_confidence = 0.05;
  OcclusionParams occlusion;
  int trunk_class = 71, pole_class = 80, car_class = 10, other_class = 0;
};

// Median distance (m) of the points `idx` of `cloud` from the nearest edge of their top view's
// bounding rectangle, at the heading (2-deg steps) where it is smallest: about the range noise
// for faces (a car's side, its end, or both as an L), more for returns spread over an area. 0
// for fewer than three points.
double edgeSpread(const Cloud& cloud, const std::vector<int>& idx);

class GeometricSegmenter : public LidarSegmenter {
 public:
  // Throws std::out_of_range when a configured class id is missing from `classes`.
  GeometricSegmenter(ClassTable classes, GeometricSegmenterParams params);
  std::string name() const override { return "geometric"; }
  std::vector<Instance> segment(const io::LabelledScan& scan, InputIssues& issues) const override;
  // The same, also listing the column candidates that were turned down and why.
  std::vector<Instance> segment(const io::LabelledScan& scan, InputIssues& issues,
                                std::vector<ColumnRejection>* rejected) const;

 private:
  ClassTable classes_;
  GeometricSegmenterParams params_;
};

}  // namespace slide::frontend
