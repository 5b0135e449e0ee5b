#pragma once
// Trunks and poles without labels, from vertical structure: the points above ground are cut
// into horizontal slices; in each slice, small compact blobs with an empty ring around them
// (in that slice: a hedge or a car beside a pole only spoils the slices it reaches) are column
// cross-sections. Cross-sections whose centres stack up (within stack_distance of each other)
// over enough slices, on a near-vertical axis, with arc-shaped cross-sections, are one column; its points are those near the
// axis up to max_height. Walls give no isolated cross-section except where seen edge-on (each
// azimuth step a stack of single returns metres apart; the scan line beyond such a stack
// continues as the face: wall_trace.h), pedestrians and cars do not reach min_top, bushes are
// too wide in every slice. The upward view above a column's top comes from scan_lines.h.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "frontend/instance.h"
#include "frontend/wall_trace.h"

namespace slide::frontend {

struct ColumnParams {
  double slice_low = 0.3;        // metres above ground: the slices cover [slice_low, slice_high)
  double slice_high = 3.3;
  double slice_height = 0.3;
  double cell = 0.1;             // planar clustering of each slice
  int min_blob_points = 1;
  double max_diameter = 1.2;     // largest extent of a cross-section
  double isolation_gap = 0.2;    // slice points between extent/2 + gap and extent/2 + gap + ring ...
  double isolation_ring = 0.5;
  double max_ring_fraction = 0.25;  // ... at most this fraction of the cross-section's points
  double single_point_ring = 1.5;   // ring width for one-point cross-sections (grazing walls)
  double stack_distance = 0.3;   // cross-section centres of one column lie this close
  int min_slices = 4;            // isolated cross-sections a column needs ...
  double min_span = 1.0;         // ... spanning this height (lowest to highest slice), and
  int min_multi_point_slices = 0;  // ... this many with more than one point (a face seen at a
                                   // grazing angle gives one point per beam, stacked too)
  double max_lean_deg = 20.0;    // axis through the cross-section centres
  // Arcs: cross-sections at least arc_min_extent wide with arc_min_points points are tested
  // for a circle (RANSAC, inliers within arc_inlier_distance) through arc_min_inliers of
  // their points with radius <= arc_max_radius_ratio * extent; at least min_arc_fraction of
  // the tested ones must pass (0 disables the test). Rejects wall pieces and foliage.
  double arc_min_extent = 0.35;
  int arc_min_points = 8;
  double arc_inlier_distance = 0.05;
  double arc_min_inliers = 0.6;
  double arc_max_radius_ratio = 0.8;
  double min_arc_fraction = 0.5;
  double min_top = 2.5;          // the column must reach this high (pedestrians do not), or
  double ceiling_margin = 0.3;   // ... to within this of the highest visible point at its range
  double max_height = 8.0;       // column points kept up to this height above ground
  double margin = 0.12;          // metres added to the column radius when collecting points
  int min_points = 8;
  double trunk_min_radius = 0.12;      // thicker columns are trunks
  double canopy_radius = 1.0;          // points farther from the axis, above min_top ...
  double canopy_min_fraction = 0.02;   // ... in this fraction of the cluster make it a trunk
  // Returns above min_top within canopy_radius + 2 m: at least ceiling_min_points of them within
  // ceiling_max_spread metres of one height (10th to 90th percentile) are a ceiling (0: off).
  // Beyond ceiling_full_range metres (0: never) the returns a patch of ceiling gives thin out
  // as 1 / range^2, and so does the count needed, down to ceiling_min_points_far, when the
  // view reaches more than ceiling_margin above every one of them (a crown cut off by the top
  // of the view is as flat at its cut; the real SemanticKITTI scans' top beam, +2 deg, gives
  // such layers of 46-95 returns at 12-18 m).
  double ceiling_max_spread = 0.0;
  int ceiling_min_points = 20;
  double ceiling_full_range = 0.0;
  int ceiling_min_points_far = 20;
  // The view above the column's top, in its azimuth, ended by at least ceiling_min_above nearer
  // returns within ceiling_max_spread of one height, no lower than ceiling_margin under the top:
  // a ceiling seen from below, the column a strip of far wall seen through doorways (0: off).
  int ceiling_min_above = 0;
  // A thin column without a canopy is a pole for sure only when its top is seen with open view
  // above it: top + end_margin below both the highest visible point at its range and
  // max_height, and no nearer return just above its top (in a forest, nearer trunks and crowns
  // hide the upper parts of farther ones). Otherwise a crown may be out of view: the call is
  // unsure; it then takes the class most sure columns of the same scan have (a forest's trunks,
  // a street's poles; a pole when there is none) with unsure_confidence (the tracker and the
  // back-end weigh class votes by it).
  double end_margin = 0.5;
  double unsure_confidence = 0.3;
  // A column whose scan lines continue as a vertical face beyond its edges (on at least
  // wall.min_fraction of its beams) is that face seen edge-on, not a column (wall_trace.h).
  WallTraceParams wall;
};

struct Column {
  std::vector<int> points;       // indices into the cloud
  Eigen::Vector2d base = Eigen::Vector2d::Zero();   // axis x, y at ground height ...
  Eigen::Vector2d slope = Eigen::Vector2d::Zero();  // ... and its change per metre up
  double radius = 0;             // half the median cross-section extent
  int slices = 0;
  bool trunk = false;            // thick, or a canopy spreads above it (else a pole)
  double confidence = 1.0;       // of the trunk / pole call (unsure_confidence when unsure)
};

// A candidate that was turned down and why (for `slide segment --explain`).
struct ColumnRejection {
  Eigen::Vector2d centre;
  std::string reason;
};

// Columns among the points `above` (indices into cloud, h = height above ground; `lines`
// indexes them). Points that end up in a column are marked in `taken` (sized like the cloud);
// points already marked are not collected. `rejected`, when given, receives the stacks that
// were turned down.
std::vector<Column> detectColumns(const Cloud& cloud, const std::vector<float>& h, const std::vector<int>& above,
                                  const ScanLines& lines, const ColumnParams& params, std::vector<char>& taken,
                                  std::vector<ColumnRejection>* rejected = nullptr);

}  // namespace slide::frontend
