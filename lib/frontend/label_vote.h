#pragma once
// A point's label settled by the points around it in 3-D: the post-processing RangeNet++
// (Milioto et al., IROS 2019, section III-D) puts after its network. A range-image labeller
// blurs labels across the image's boundaries: pixels of a wall just above a table's edge, or
// of a chair in front of it, come out "table" though they lie a metre away from any table in
// 3-D, and a handful of them per frame forms a table of their own. Here each point carrying an
// object label takes the label most of the points in the 3 x 3 x 3 cells around its own carry
// (itself included; a tie keeps its own): a strip of wall called table lies among wall points
// and leaves the objects, a chair's edge called table rejoins its chair. Cells, not a radius:
// all points of one cell see the same block, so the vote costs a pass over the scan however
// densely a near wall is sampled.
#include <cstdint>
#include <functional>
#include <vector>

#include "io/kitti_scan.h"

namespace slide::frontend {

struct LabelVoteParams {
  double cell = 0.0;        // metres, a cell's side; 0: off (the labels as they came)
  double max_range = 80.0;  // metres, horizontal: points beyond neither vote nor are voted on
};

// The scan's labels after the vote. Only points for which `is_object(label)` holds are voted
// on; every finite point within max_range votes (a point too far above or below to have a cell
// keeps its label and has no vote). Same size as scan.semantic. Requires labels
// (scan.hasLabels()).
std::vector<uint16_t> voteLabels(const io::LabelledScan& scan, const std::function<bool(uint16_t)>& is_object,
                                 const LabelVoteParams& params);

}  // namespace slide::frontend
