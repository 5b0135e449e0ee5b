#include "eval/map_agreement.h"

#include <cmath>
#include <map>

#include "eval/alignment.h"

namespace slide::eval {

namespace {

// Index in `map` of the landmark matched to each true object, by true object.
std::map<std::size_t, std::size_t> matchedByTruth(const std::vector<Object>& map, const Pose& T_world,
                                                  const std::vector<Object>& truth, const ObjectMatchOptions& mo) {
  std::vector<Object> in_world;
  in_world.reserve(map.size());
  for (const Object& o : map) in_world.push_back(transformObject(T_world, o));
  std::map<std::size_t, std::size_t> out;
  for (const ObjectMatch& m : scoreObjectMap(in_world, truth, mo).matches) out[m.gt] = m.est;
  return out;
}

}  // namespace

SharedLandmarks sharedLandmarks(const std::vector<Object>& map_a, const Pose& T_world_a, const std::vector<Object>& map_b,
                                const Pose& T_world_b, const std::vector<Object>& truth, const ObjectMatchOptions& mo) {
  const auto a = matchedByTruth(map_a, T_world_a, truth, mo), b = matchedByTruth(map_b, T_world_b, truth, mo);
  SharedLandmarks out;
  for (const auto& [gt, ia] : a)
    if (const auto it = b.find(gt); it != b.end()) {
      out.in_a.push_back(map_a[ia].position());
      out.in_b.push_back(map_b[it->second].position());
    }
  return out;
}

std::optional<Pose> mapAlignment(const SharedLandmarks& shared) {
  if (shared.in_a.size() < 3) return std::nullopt;
  auto flat = [](std::vector<Eigen::Vector3d> v) {
    for (Eigen::Vector3d& p : v) p.z() = 0;
    return v;
  };
  return align(flat(shared.in_b), flat(shared.in_a), TrajectoryAlignment::Yaw4Dof).T;
}

std::vector<double> landmarkDistances(const SharedLandmarks& shared, const Pose& T_a_b) {
  std::vector<double> out;
  for (std::size_t k = 0; k < shared.in_a.size(); ++k)
    out.push_back((T_a_b * shared.in_b[k] - shared.in_a[k]).head<2>().norm());
  return out;
}

HorizontalError horizontalError(const Pose& estimate, const Pose& reference) {
  const double yaw = xyzYawOf(estimate)[3] - xyzYawOf(reference)[3];
  return {(estimate.translation() - reference.translation()).head<2>().norm(),
          std::abs(wrapAngle(yaw)) * 180.0 / M_PI};
}

}  // namespace slide::eval
