#pragma once
// Is a column candidate a vertical face seen at a grazing angle? A vertical face returns, at
// each azimuth step of a spinning LiDAR, one stack of points at the same (x, y) on every beam
// that hits it; seen nearly edge-on, those stacks lie metres apart, so each one alone looks
// like a thin isolated column (one return per beam) to the cross-section tests. What gives it
// away is the scan line: on a beam through the column, the next returns beyond the column's
// edge in azimuth continue it on a straight line in the plane, at a regular spacing (the face
// sampled at the next azimuth steps; or, for a lone return, its neighbours on both sides lie on
// one line with it). A free-standing trunk or pole has its background there:
// farther away, off that line, or nothing.
// The same holds round a corner: a stack seen just behind the end of a nearer face (the next
// return beyond its edge begins a straight run of returns longer than any column is wide) is
// the hidden continuation of that face, or at best a column whose isolation cannot be seen.
#include <vector>

#include "frontend/scan_lines.h"

namespace slide::frontend {

struct WallTraceParams {
  double window_deg = 2.0;       // azimuth searched beyond a column edge for the next returns ...
  double window_length = 2.5;    // ... or as much as spans this many metres at the edge's range (at most 10 deg)
  double beam_tolerance_deg = 0.1;  // elevation difference of returns on the same beam
  double max_step = 8.0;         // metres (horizontal) between consecutive returns on the face
  double line_tolerance = 0.08;  // metres: distance of the column edge from the line through the next two returns
  double max_step_ratio = 3.0;   // consecutive steps along the face differ at most by this factor
  double corner_run = 0.6;       // a straight run of returns this long beside a stack behind it is a face (0: off)
  int max_run_returns = 12;      // returns followed along that run
  double min_fraction = 0.5;     // share of the column's beams continued as a face that makes it one (0: off)
};

// Share of the beams through `column` (indices into the cloud `lines` indexes; `in_column`
// marks them, sized like the cloud) whose next returns beyond either edge of the column
// continue it as a face (straight on, round a corner, or between two; see above). 0 for an
// empty column. With params.min_fraction > 0 it stops once the share is decided against it:
// the share returned is then a lower bound when >= min_fraction, an upper bound otherwise.
double faceFraction(const Cloud& cloud, const ScanLines& lines, const std::vector<int>& column,
                    const std::vector<char>& in_column, const WallTraceParams& params);

}  // namespace slide::frontend
