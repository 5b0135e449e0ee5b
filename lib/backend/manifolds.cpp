// Manifolds of the pose and cylinder parameter blocks.
#include <ceres/manifold.h>
#include <ceres/product_manifold.h>
#include <ceres/sphere_manifold.h>

#include "backend/factors.h"

namespace slide::backend {

ceres::Manifold* newPoseManifold() {
  return new ceres::ProductManifold<ceres::EuclideanManifold<3>, ceres::EigenQuaternionManifold>();
}

ceres::Manifold* newCylinderManifold() {
  return new ceres::ProductManifold<ceres::EuclideanManifold<3>, ceres::SphereManifold<3>, ceres::EuclideanManifold<1>>();
}

}  // namespace slide::backend
