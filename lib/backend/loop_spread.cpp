#include "backend/loop_spread.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <memory>

#include "backend/pose_block.h"

namespace slide::backend {

std::vector<Pose> spreadLoopError(const std::vector<Pose>& chain, const std::vector<Pose>& fixed,
                                  const std::vector<LoopSpread::Closure>& closures, const PoseSigma& loop_sigma,
                                  const LoopSpreadNoise& noise) {
  const int n = static_cast<int>(chain.size());
  if (n < 2 || closures.empty()) return chain;
  std::vector<PoseBlock> blocks(n), anchors(fixed.size());
  for (int i = 0; i < n; ++i) blocks[i] = toPoseBlock(chain[i]);
  for (std::size_t k = 0; k < fixed.size(); ++k) anchors[k] = toPoseBlock(fixed[k]);
  std::unique_ptr<ceres::Manifold> manifold(newPoseManifold());
  ceres::Problem::Options po;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  for (auto& block : blocks) problem.AddParameterBlock(block.data(), 7, manifold.get());
  problem.SetParameterBlockConstant(blocks[0].data());
  for (int i = 0; i + 1 < n; ++i) {
    const Pose rel = chain[i].inverse() * chain[i + 1];
    const double d = rel.translation().norm();
    PoseSigma s;
    s.head<3>().setConstant(std::max(noise.translation_floor, noise.translation_per_m * d));
    s.tail<3>().setConstant(std::max(noise.rotation_floor, noise.rotation_per_m * d));
    problem.AddResidualBlock(relativePoseFactor(rel, s), nullptr, blocks[i].data(), blocks[i + 1].data());
  }
  auto block = [&](int index) -> double* {
    if (index >= 0) return index < n ? blocks[index].data() : nullptr;
    const std::size_t k = static_cast<std::size_t>(-index - 1);
    if (k >= anchors.size()) return nullptr;
    if (!problem.HasParameterBlock(anchors[k].data())) {
      problem.AddParameterBlock(anchors[k].data(), 7, manifold.get());
      problem.SetParameterBlockConstant(anchors[k].data());
    }
    return anchors[k].data();
  };
  for (const LoopSpread::Closure& c : closures) {
    double* a = block(c.a);
    double* b = block(c.b);
    if (a && b && a != b) problem.AddResidualBlock(relativePoseFactor(c.T_a_b, loop_sigma), nullptr, a, b);
  }
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

void spreadLoops(std::vector<std::array<double, 7>>& values, const std::vector<LoopSpread>& spreads,
                 const std::vector<LandmarkObservers>& landmarks, const PoseSigma& loop_sigma,
                 const LoopSpreadNoise& noise) {
  std::vector<Pose> correction(values.size(), Pose::Identity());
  std::vector<char> moved(values.size(), 0);
  for (const LoopSpread& spread : spreads) {
    std::vector<Pose> before(spread.chain.size()), fixed(spread.fixed.size());
    for (std::size_t i = 0; i < spread.chain.size(); ++i) before[i] = fromPoseBlock(values[spread.chain[i]].data());
    for (std::size_t k = 0; k < spread.fixed.size(); ++k) fixed[k] = fromPoseBlock(values[spread.fixed[k]].data());
    const std::vector<Pose> after = spreadLoopError(before, fixed, spread.closures, loop_sigma, noise);
    for (std::size_t i = 0; i < spread.chain.size(); ++i) {
      correction[spread.chain[i]] = after[i] * before[i].inverse();
      moved[spread.chain[i]] = 1;
      const PoseBlock block = toPoseBlock(after[i]);
      std::copy(block.begin(), block.end(), values[spread.chain[i]].begin());
    }
    for (const LandmarkObservers& lm : landmarks) {
      const Pose* C = nullptr;
      double least = 1e300;
      for (int o : lm.observers) {
        const double d = moved[o] ? correction[o].translation().norm() : 0.0;
        if (d < least) least = d, C = moved[o] ? &correction[o] : nullptr;
      }
      if (C) moveLandmarkBlock(values[lm.var].data(), lm.shape, *C);
    }
    for (int v : spread.chain) moved[v] = 0;
  }
}

void moveLandmarkBlock(double* v, Shape shape, const Pose& C) {
  if (shape == Shape::Cuboid) {
    const PoseBlock block = toPoseBlock(C * fromPoseBlock(v));
    std::copy(block.begin(), block.end(), v);
  } else if (shape == Shape::Cylinder) {
    const Eigen::Vector3d root = C * Eigen::Vector3d(v[0], v[1], v[2]);
    const Eigen::Vector3d axis = C.linear() * Eigen::Vector3d(v[3], v[4], v[5]);
    for (int k = 0; k < 3; ++k) v[k] = root[k], v[3 + k] = axis[k];
  } else {
    const Eigen::Vector3d c = C * Eigen::Vector3d(v[0], v[1], v[2]);
    for (int k = 0; k < 3; ++k) v[k] = c[k];
  }
}

}  // namespace slide::backend
