#include "place/simplex_descriptor.h"

#include <algorithm>

namespace slide::place {

std::vector<SimplexDescriptor> describeTriangles(const std::vector<Landmark>& lms, const std::vector<Triangle>& tris) {
  std::vector<SimplexDescriptor> out;
  out.reserve(tris.size());
  for (const Triangle& t : tris) {
    const Eigen::Vector2d c = (lms[t[0]].p + lms[t[1]].p + lms[t[2]].p).head<2>() / 3.0;
    std::array<std::pair<double, std::uint32_t>, 3> v;
    for (int k = 0; k < 3; ++k) v[k] = {(lms[t[k]].p.head<2>() - c).norm(), t[k]};
    std::sort(v.begin(), v.end(), [&](const auto& x, const auto& y) {
      if (x.first != y.first) return x.first < y.first;
      if (lms[x.second].class_id != lms[y.second].class_id) return lms[x.second].class_id < lms[y.second].class_id;
      return x.second < y.second;
    });
    SimplexDescriptor d;
    for (int k = 0; k < 3; ++k) {
      d.distances[k] = v[k].first;
      d.vertices[k] = v[k].second;
      d.classes[k] = lms[v[k].second].class_id;
    }
    out.push_back(d);
  }
  return out;
}

}  // namespace slide::place
