#include "objects/object.h"

#include <cmath>

namespace slide {

namespace {
template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;
}  // namespace

Eigen::Vector3d Object::position() const {
  return std::visit(Overloaded{[](const Cuboid& c) -> Eigen::Vector3d { return c.pose.translation(); },
                               [](const Cylinder& c) -> Eigen::Vector3d { return c.root + 0.5 * c.length * c.axis; },
                               [](const Ellipsoid& e) -> Eigen::Vector3d { return e.centroid; }},
                    model);
}

Eigen::Vector3d Object::extent() const {
  return std::visit(Overloaded{[](const Cuboid& c) -> Eigen::Vector3d { return c.dims; },
                               [](const Cylinder& c) -> Eigen::Vector3d { return {2 * c.radius, 2 * c.radius, c.length}; },
                               [](const Ellipsoid& e) -> Eigen::Vector3d { return {2 * e.radius, 2 * e.radius, e.height}; }},
                    model);
}

bool Object::isFinite() const {
  const bool ok = std::visit(
      Overloaded{[](const Cuboid& c) { return c.pose.matrix().allFinite() && c.dims.allFinite(); },
                 [](const Cylinder& c) {
                   return c.root.allFinite() && c.axis.allFinite() && std::isfinite(c.radius) && std::isfinite(c.length);
                 },
                 [](const Ellipsoid& e) { return e.centroid.allFinite() && std::isfinite(e.radius) && std::isfinite(e.height); }},
      model);
  const bool other_ok =
      !other_reading || (other_reading->pose.matrix().allFinite() && other_reading->dims.allFinite());
  return ok && other_ok && std::isfinite(confidence);
}

const char* shapeName(Shape s) {
  switch (s) {
    case Shape::Cuboid: return "cuboid";
    case Shape::Cylinder: return "cylinder";
    case Shape::Ellipsoid: return "ellipsoid";
  }
  return "unknown";
}

Object transformObject(const Pose& T, const Object& o) {
  Object out = o;
  out.model = std::visit(Overloaded{[&](const Cuboid& c) -> ObjectModel { return Cuboid{T * c.pose, c.dims}; },
                                    [&](const Cylinder& c) -> ObjectModel {
                                      return Cylinder{T * c.root, T.linear() * c.axis, c.radius, c.length};
                                    },
                                    [&](const Ellipsoid& e) -> ObjectModel { return Ellipsoid{T * e.centroid, e.radius, e.height}; }},
                         o.model);
  if (o.other_reading) out.other_reading = Cuboid{T * o.other_reading->pose, o.other_reading->dims};
  return out;
}

}  // namespace slide
