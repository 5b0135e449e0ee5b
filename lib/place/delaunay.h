#pragma once
// 2-D Delaunay triangulation of landmark positions (OpenCV's incremental Subdiv2D).
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace slide::place {

using Triangle = std::array<std::uint32_t, 3>;  // indices into the input points

// Triangles of the Delaunay triangulation of the xy points. Points within 1 mm of an earlier
// point are merged into it; non-finite points are skipped; degenerate (collinear) input
// gives no triangles; slivers of near-zero area are dropped. `out_of_time`, when given, is
// polled during the insertions; once it says true no triangles are returned.
std::vector<Triangle> delaunay2d(const std::vector<Eigen::Vector2d>& pts,
                                 const std::function<bool()>& out_of_time = nullptr);

}  // namespace slide::place
