#include "backend/loop_spread.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <memory>

#include "backend/optimizer.h"
#include "backend/pose_block.h"

namespace slide {

std::vector<Pose> spreadLoopError(const std::vector<Pose>& poses, int b, const Pose& T_a_b, const PoseSigma& loop_sigma,
                                  const LoopSpreadNoise& noise) {
  const int n = static_cast<int>(poses.size());
  if (n < 2 || b <= 0 || b >= n) return poses;
  std::vector<PoseBlock> blocks(n);
  for (int i = 0; i < n; ++i) blocks[i] = toPoseBlock(poses[i]);
  std::unique_ptr<ceres::Manifold> manifold(newPoseManifold());
  ceres::Problem::Options po;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  for (auto& block : blocks) problem.AddParameterBlock(block.data(), 7, manifold.get());
  problem.SetParameterBlockConstant(blocks[0].data());
  for (int i = 0; i + 1 < n; ++i) {
    const Pose rel = poses[i].inverse() * poses[i + 1];
    const double d = rel.translation().norm();
    PoseSigma s;
    s.head<3>().setConstant(std::max(noise.translation_floor, noise.translation_per_m * d));
    s.tail<3>().setConstant(std::max(noise.rotation_floor, noise.rotation_per_m * d));
    problem.AddResidualBlock(relativePoseFactor(rel, s), nullptr, blocks[i].data(), blocks[i + 1].data());
  }
  problem.AddResidualBlock(relativePoseFactor(T_a_b, loop_sigma), nullptr, blocks[0].data(), blocks[b].data());
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  o.max_num_iterations = 10;
  o.initial_trust_region_radius = 1e8;
  o.function_tolerance = 1e-8;
  o.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(o, &problem, &summary);
  std::vector<Pose> out(n);
  for (int i = 0; i < n; ++i) out[i] = fromPoseBlock(blocks[i].data());
  return out;
}

void Optimizer::spreadLoop(const KeyPose& a, const KeyPose& b, const Pose& T_a_b) {
  const std::vector<int>& list = robots_[a.robot].keyposes;
  const auto first = std::find_if(list.begin(), list.end(), [&](int k) { return keyposes_[k].seq == a.seq; });
  std::vector<int> vars;
  int b_index = -1;
  for (auto it = first; it != list.end(); ++it) {
    if (keyposes_[*it].seq == b.seq) b_index = static_cast<int>(vars.size());
    vars.push_back(keyposes_[*it].var);
  }
  if (b_index <= 0) return;
  std::vector<Pose> before(vars.size());
  for (std::size_t i = 0; i < vars.size(); ++i) before[i] = poseOf(vars[i]);
  PoseSigma loop_sigma;
  loop_sigma << cfg_.loop_translation_sigma, cfg_.loop_translation_sigma, cfg_.loop_translation_sigma,
      cfg_.loop_rotation_sigma, cfg_.loop_rotation_sigma, cfg_.loop_rotation_sigma;
  const LoopSpreadNoise noise{cfg_.odom_translation_floor, cfg_.odom_translation_per_m, cfg_.odom_rotation_floor,
                              cfg_.odom_rotation_per_m};
  const std::vector<Pose> after = spreadLoopError(before, b_index, T_a_b, loop_sigma, noise);
  // Correction of each moved pose, in the host frame, by variable.
  std::vector<Pose> correction(graph_.numVariables(), Pose::Identity());
  std::vector<char> moved(graph_.numVariables(), 0);
  for (std::size_t i = 0; i < vars.size(); ++i) {
    correction[vars[i]] = after[i] * before[i].inverse();
    moved[vars[i]] = 1;
    const PoseBlock block = toPoseBlock(after[i]);
    std::copy(block.begin(), block.end(), graph_.value(vars[i]));
  }
  // Each landmark follows the observer that moved least (those seen from before the loop stay).
  for (const Landmark& lm : landmarks_) {
    if (!lm.alive || lm.seen.empty()) continue;
    const Pose* C = nullptr;
    double least = 1e300;
    for (const Observation& o : lm.seen) {
      const double d = moved[o.pose_var] ? correction[o.pose_var].translation().norm() : 0.0;
      if (d < least) least = d, C = moved[o.pose_var] ? &correction[o.pose_var] : nullptr;
    }
    if (C) moveLandmark(lm, *C);
  }
}

void Optimizer::moveLandmark(const Landmark& lm, const Pose& C) {
  double* v = graph_.value(lm.var);
  if (lm.shape == Shape::Cuboid) {
    const PoseBlock block = toPoseBlock(C * fromPoseBlock(v));
    std::copy(block.begin(), block.end(), v);
  } else if (lm.shape == Shape::Cylinder) {
    const Eigen::Vector3d root = C * Eigen::Vector3d(v[0], v[1], v[2]);
    const Eigen::Vector3d axis = C.linear() * Eigen::Vector3d(v[3], v[4], v[5]);
    for (int k = 0; k < 3; ++k) v[k] = root[k], v[3 + k] = axis[k];
  } else {
    const Eigen::Vector3d c = C * Eigen::Vector3d(v[0], v[1], v[2]);
    for (int k = 0; k < 3; ++k) v[k] = c[k];
  }
}

}  // namespace slide
