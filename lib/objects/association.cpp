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
// The box's length axis and half extents in the horizontal plane, or nothing when it stands on its end.
bool footprint(const Cuboid& c, double margin, Eigen::Vector2d& along, Eigen::Vector2d& half) {
  const Eigen::Vector2d x = c.pose.rotation().col(0).head<2>();
  if (!(x.norm() > 1e-6)) return false;
  along = x.normalized();
  half = 0.5 * c.dims.head<2>() + Eigen::Vector2d::Constant(margin);
  return true;
}
}  // namespace

bool footprintsOverlap(const Cuboid& a, const Cuboid& b, double margin) {
  Eigen::Vector2d ua, ha, ub, hb;
  if (!footprint(a, margin, ua, ha) || !footprint(b, margin, ub, hb)) return true;
  const Eigen::Vector2d va(-ua.y(), ua.x()), vb(-ub.y(), ub.x());
  const Eigen::Vector2d d = (b.pose.translation() - a.pose.translation()).head<2>();
  for (const Eigen::Vector2d& n : {ua, va, ub, vb}) {
    const double ra = ha.x() * std::abs(ua.dot(n)) + ha.y() * std::abs(va.dot(n));
    const double rb = hb.x() * std::abs(ub.dot(n)) + hb.y() * std::abs(vb.dot(n));
    if (std::abs(d.dot(n)) > ra + rb) return false;
  }
  return true;
}

Object otherReadingOf(const Object& detection) {
  if (!detection.other_reading || !std::holds_alternative<Cuboid>(detection.model)) return detection;
  Object other = detection;
  other.model = *detection.other_reading;
  other.other_reading = std::get<Cuboid>(detection.model);
  return other;
}

Object nearestReading(const Object& detection, const Object& landmark) {
  if (!detection.other_reading || !std::holds_alternative<Cuboid>(detection.model)) return detection;
  const Object other = otherReadingOf(detection);
  const auto score = [&](const Object& o) { return associationDistance(o, landmark) + modelDifference(o, landmark); };
  return score(other) < score(detection) ? other : detection;
}

double headingOf(const Cuboid& box) {
  const Eigen::Matrix3d& R = box.pose.linear();
  return std::atan2(R(1, 0), R(0, 0));
}

bool otherReadingAgreesMore(const Object& detection, const std::vector<double>& whole_headings) {
  const auto* first = std::get_if<Cuboid>(&detection.model);
  return first && detection.other_reading && otherReadingAgreesMore(*first, *detection.other_reading, whole_headings);
}

bool otherReadingAgreesMore(const Cuboid& first, const Cuboid& second, const std::vector<double>& whole_headings) {
  const double a = headingOf(first), b = headingOf(second);
  double vote = 0;
  for (const double h : whole_headings) vote += std::cos(2 * (b - h)) - std::cos(2 * (a - h));
  return vote > 0;
}

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

}  // namespace slide
