#include "plot/object_shapes.h"

#include <algorithm>
#include <cmath>

namespace slide::plot {

namespace {
template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

std::vector<Eigen::Vector2d> project(const std::vector<Eigen::Vector3d>& pts, const View& v) {
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : pts) out.push_back(v.project(p));
  return out;
}

// Shade of a face with outward unit normal n: top faces full colour, sides darker.
double shadeOf(const Eigen::Vector3d& n) { return 0.62 + 0.38 * std::max(0.0, n.z()); }

void cuboidFacets(const Cuboid& c, const View& v, ObjectFacets& out) {
  const Eigen::Vector3d h = 0.5 * c.dims;
  const Eigen::Vector3d d = v.towardsViewer();
  std::vector<Eigen::Vector3d> all;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {-1, 1}) {
      const Eigen::Vector3d n = sign * c.pose.linear().col(axis);
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      std::vector<Eigen::Vector3d> face;
      for (auto [s1, s2] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        Eigen::Vector3d local;
        local[axis] = sign * h[axis];
        local[a1] = s1 * h[a1];
        local[a2] = s2 * h[a2];
        face.push_back(c.pose * local);
      }
      all.insert(all.end(), face.begin(), face.end());
      if (n.dot(d) > 1e-9) out.facets.push_back({project(face, v), shadeOf(n)});
    }
  }
  out.silhouette = convexHull(project(all, v));
}

std::vector<Eigen::Vector3d> ring(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis, double r, int n) {
  Eigen::Vector3d a = axis.normalized();
  Eigen::Vector3d u = a.unitOrthogonal(), w = a.cross(u);
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    out.push_back(centre + r * (std::cos(t) * u + std::sin(t) * w));
  }
  return out;
}

void cylinderFacets(const Cylinder& c, const View& v, ObjectFacets& out) {
  const Eigen::Vector3d axis = c.axis.norm() > 1e-9 ? c.axis.normalized() : Eigen::Vector3d::UnitZ();
  const auto bottom = ring(c.root, axis, c.radius, 36);
  const auto top = ring(c.root + c.length * axis, axis, c.radius, 36);
  std::vector<Eigen::Vector3d> all = bottom;
  all.insert(all.end(), top.begin(), top.end());
  out.silhouette = convexHull(project(all, v));
  out.facets.push_back({out.silhouette, 0.72});
  const Eigen::Vector3d d = v.towardsViewer();
  if (axis.dot(d) > 1e-9) out.facets.push_back({project(top, v), 1.0});
  else if (axis.dot(d) < -1e-9) out.facets.push_back({project(bottom, v), 0.6});
}

void ellipsoidFacets(const Ellipsoid& e, const View& v, ObjectFacets& out) {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 36; ++i)
    for (int j = 1; j < 12; ++j) {
      const double az = 2 * M_PI * i / 36, el = -M_PI / 2 + M_PI * j / 12;
      pts.push_back(e.centroid + Eigen::Vector3d(e.radius * std::cos(el) * std::cos(az),
                                                 e.radius * std::cos(el) * std::sin(az), 0.5 * e.height * std::sin(el)));
    }
  pts.push_back(e.centroid + Eigen::Vector3d(0, 0, 0.5 * e.height));
  pts.push_back(e.centroid - Eigen::Vector3d(0, 0, 0.5 * e.height));
  out.silhouette = convexHull(project(pts, v));
  out.facets.push_back({out.silhouette, 0.9});
}
}  // namespace

std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> pts) {
  std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  pts.erase(std::unique(pts.begin(), pts.end(), [](const auto& a, const auto& b) { return (a - b).norm() < 1e-12; }),
            pts.end());
  if (pts.size() < 3) return pts;
  std::vector<Eigen::Vector2d> h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], pts[i - 1]) <= 0) --k;
    h[k++] = pts[i - 1];
  }
  h.resize(k - 1);
  return h;
}

ObjectFacets objectFacets(const Object& o, const View& view) {
  ObjectFacets out;
  out.depth = view.depth(o.position());
  std::visit(Overloaded{[&](const Cuboid& c) { cuboidFacets(c, view, out); },
                        [&](const Cylinder& c) { cylinderFacets(c, view, out); },
                        [&](const Ellipsoid& e) { ellipsoidFacets(e, view, out); }},
             o.model);
  return out;
}

}  // namespace slide::plot
