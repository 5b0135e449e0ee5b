#include "objects/association.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slide {

namespace {
double distanceToAxis(const Cylinder& c, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - c.root;
  return (d - d.dot(c.axis) * c.axis).norm();
}
}  // namespace

double associationDistance(const Object& a, const Object& b) {
  const auto* ca = std::get_if<Cylinder>(&a.model);
  const auto* cb = std::get_if<Cylinder>(&b.model);
  if (ca && cb) return 0.5 * (distanceToAxis(*ca, b.position()) + distanceToAxis(*cb, a.position()));
  return (a.position() - b.position()).norm();
}

double modelDifference(const Object& a, const Object& b) {
  if (a.shape() != b.shape()) return std::numeric_limits<double>::infinity();
  switch (a.shape()) {
    case Shape::Cuboid: {
      const Eigen::Vector3d da = a.extent(), db = b.extent();
      const Eigen::Vector3d swapped(db.y(), db.x(), db.z());
      return std::min((da - db).norm(), (da - swapped).norm());
    }
    case Shape::Cylinder:
      return std::abs(std::get<Cylinder>(a.model).radius - std::get<Cylinder>(b.model).radius);
    case Shape::Ellipsoid: {
      const auto& ea = std::get<Ellipsoid>(a.model);
      const auto& eb = std::get<Ellipsoid>(b.model);
      return std::hypot(ea.radius - eb.radius, ea.height - eb.height);
    }
  }
  return std::numeric_limits<double>::infinity();
}

bool associable(const Object& a, const Object& b, const ClassTable& classes) {
  if (a.class_id != b.class_id) return false;
  const ClassInfo* c = classes.find(a.class_id);
  if (!c) return false;
  return associationDistance(a, b) <= c->association_distance && modelDifference(a, b) <= c->model_difference;
}

}  // namespace slide
