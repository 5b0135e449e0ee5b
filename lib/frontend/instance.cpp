#include "frontend/instance.h"

namespace slide::frontend {

Cloud transformCloud(const Pose& T, const Cloud& cloud) {
  const Eigen::Matrix3f R = T.linear().cast<float>();
  const Eigen::Vector3f t = T.translation().cast<float>();
  Cloud out;
  out.reserve(cloud.size());
  for (const auto& p : cloud) out.push_back(R * p + t);
  return out;
}

Eigen::Vector3d centroidOf(const Cloud& cloud) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& p : cloud) sum += p.cast<double>();
  return cloud.empty() ? sum : Eigen::Vector3d(sum / static_cast<double>(cloud.size()));
}

}  // namespace slide::frontend
