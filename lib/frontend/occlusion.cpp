#include "frontend/occlusion.h"

namespace slide::frontend {

double occludedFraction(const Cloud& cloud, const ScanLines& lines, const std::vector<int>& points,
                        const std::vector<char>& in_set, const OcclusionParams& p) {
  const std::vector<ScanLines::BeamEdges> beams = lines.beamEdges(points, p.beam_tolerance_deg);
  if (beams.empty()) return 0.0;
  auto hidden = [&](int edge, int direction) {
    const std::vector<int> n = lines.next(edge, direction, 1, p.window_deg, p.beam_tolerance_deg, in_set);
    return !n.empty() && cloud[n[0]].head<2>().norm() < cloud[edge].head<2>().norm() - p.min_gap;
  };
  int occluded = 0;
  for (const auto& b : beams) occluded += hidden(b.high, +1) || hidden(b.low, -1);
  return static_cast<double>(occluded) / beams.size();
}

}  // namespace slide::frontend
