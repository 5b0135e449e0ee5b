#include "frontend/shape_fit.h"

namespace slide::frontend {

namespace {
// Whether the model's extents pass the class's size gates (*why says which does not). Cylinders:
// only the radius is gated (the visible length depends on occlusion).
bool withinClassSize(const Object& o, const ClassInfo& info, const FitParams& p, std::string* why) {
  const Eigen::Vector3d ext = o.extent();
  const int gated = info.shape == Shape::Cylinder ? 2 : 3;
  for (int i = 0; i < gated; ++i) {
    const double tol = info.shape == Shape::Cuboid ? p.cuboid.size_tolerance : 1.0;
    if (ext[i] > info.size_max[i] * tol || (info.shape != Shape::Cuboid && ext[i] < info.size_min[i] * 0.5)) {
      if (why) *why = "extent " + std::to_string(ext[i]) + " m on axis " + std::to_string(i) + " outside " +
                      info.name + " size range";
      return false;
    }
  }
  return true;
}
}  // namespace

std::optional<Object> fitObject(const Cloud& pts, int class_id, const ClassTable& classes, const FitParams& p,
                                const Eigen::Vector3d& viewpoint, std::string* why,
                                std::optional<Object>* other_reading, const Cloud* free_space) {
  if (other_reading) other_reading->reset();
  const ClassInfo* info = classes.find(class_id);
  if (!info) {
    if (why) *why = "unknown class " + std::to_string(class_id);
    return std::nullopt;
  }
  Object o;
  o.class_id = class_id;
  std::optional<Cuboid> other;
  switch (info->shape) {
    case Shape::Cuboid: {
      auto box = fitCuboid(pts, p.cuboid, viewpoint, info->size_min, info->size_max, info->typicalSize(), why,
                           other_reading ? &other : nullptr, free_space);
      if (!box) return std::nullopt;
      o.model = *box;
      break;
    }
    case Shape::Cylinder: {
      auto cyl = fitCylinder(pts, p.cylinder, viewpoint, why);
      if (!cyl) return std::nullopt;
      o.model = *cyl;
      break;
    }
    case Shape::Ellipsoid: {
      const Eigen::Vector3d typical = info->typicalSize();
      auto ell = fitEllipsoid(pts, p.ellipsoid, viewpoint, 0.5 * std::min(typical.x(), typical.y()), why);
      if (!ell) return std::nullopt;
      o.model = *ell;
      break;
    }
  }
  if (!o.isFinite()) {
    if (why) *why = "non-finite model";
    return std::nullopt;
  }
  if (!withinClassSize(o, *info, p, why)) return std::nullopt;
  if (other) {
    Object alt = o;
    alt.model = *other;
    if (alt.isFinite() && withinClassSize(alt, *info, p, nullptr)) *other_reading = alt;
  }
  return o;
}

}  // namespace slide::frontend
