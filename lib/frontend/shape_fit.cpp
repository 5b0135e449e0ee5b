#include "frontend/shape_fit.h"

namespace slide::frontend {

std::optional<Object> fitObject(const Cloud& pts, int class_id, const ClassTable& classes, const FitParams& p,
                                const Eigen::Vector3d& viewpoint, std::string* why) {
  const ClassInfo* info = classes.find(class_id);
  if (!info) {
    if (why) *why = "unknown class " + std::to_string(class_id);
    return std::nullopt;
  }
  Object o;
  o.class_id = class_id;
  switch (info->shape) {
    case Shape::Cuboid: {
      auto box = fitCuboid(pts, p.cuboid, viewpoint, info->size_min, info->size_max, info->typicalSize(), why);
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
  // Cylinders: only the radius is gated (the visible length depends on occlusion).
  const Eigen::Vector3d ext = o.extent();
  const int gated = info->shape == Shape::Cylinder ? 2 : 3;
  for (int i = 0; i < gated; ++i) {
    const double tol = info->shape == Shape::Cuboid ? p.cuboid.size_tolerance : 1.0;
    if (ext[i] > info->size_max[i] * tol || (info->shape != Shape::Cuboid && ext[i] < info->size_min[i] * 0.5)) {
      if (why) *why = "extent " + std::to_string(ext[i]) + " m on axis " + std::to_string(i) + " outside " +
                      info->name + " size range";
      return std::nullopt;
    }
  }
  return o;
}

}  // namespace slide::frontend
