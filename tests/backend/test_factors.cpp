// Every back-end factor: zero residual when the measurement agrees with the state, and
// automatic-differentiation Jacobians equal to numeric (central difference) ones.
#include <ceres/cost_function.h>
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

#include "backend/factors.h"
#include "backend/pose_block.h"

using namespace slide;

namespace {

Pose randomPose(std::mt19937& rng, double spread = 3.0) {
  std::uniform_real_distribution<double> u(-1, 1);
  return poseFromXyzRpy({spread * u(rng), spread * u(rng), spread * u(rng)}, 0.3 * u(rng), 0.3 * u(rng), 3 * u(rng));
}

struct Eval {
  std::vector<double> residual;
  std::vector<std::vector<double>> jacobians;
};

Eval evaluate(const ceres::CostFunction& f, const std::vector<const double*>& blocks) {
  Eval e;
  e.residual.resize(f.num_residuals());
  std::vector<double*> jac;
  for (int size : f.parameter_block_sizes()) e.jacobians.emplace_back(f.num_residuals() * size);
  for (auto& j : e.jacobians) jac.push_back(j.data());
  EXPECT_TRUE(f.Evaluate(blocks.data(), e.residual.data(), jac.data()));
  return e;
}

// Compares the autodiff and numeric versions of one factor at `blocks`.
void expectSameJacobians(ceres::CostFunction* automatic, ceres::CostFunction* numeric,
                         const std::vector<const double*>& blocks) {
  std::unique_ptr<ceres::CostFunction> a(automatic), n(numeric);
  const Eval ea = evaluate(*a, blocks), en = evaluate(*n, blocks);
  for (std::size_t i = 0; i < ea.residual.size(); ++i) EXPECT_NEAR(ea.residual[i], en.residual[i], 1e-9);
  for (std::size_t b = 0; b < ea.jacobians.size(); ++b) {
    double scale = 1.0;
    for (double v : ea.jacobians[b]) scale = std::max(scale, std::abs(v));
    for (std::size_t i = 0; i < ea.jacobians[b].size(); ++i)
      EXPECT_NEAR(ea.jacobians[b][i], en.jacobians[b][i], 1e-6 * scale) << "block " << b << " entry " << i;
  }
}

double residualNorm(ceres::CostFunction* f, const std::vector<const double*>& blocks) {
  std::unique_ptr<ceres::CostFunction> owned(f);
  const Eval e = evaluate(*f, blocks);
  double s = 0;
  for (double r : e.residual) s += r * r;
  return std::sqrt(s);
}

backend::PoseSigma sigma(double t, double r) {
  backend::PoseSigma s;
  s << t, t, t, r, r, r;
  return s;
}

}  // namespace

TEST(BackendFactors, RelativePoseMatchesNumeric) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 5; ++trial) {
    const Pose A = randomPose(rng), B = randomPose(rng);
    const backend::PoseBlock a = backend::toPoseBlock(A), b = backend::toPoseBlock(B);
    const Pose M = A.inverse() * B;
    EXPECT_LT(residualNorm(backend::relativePoseFactor(M, sigma(0.1, 0.01)), {a.data(), b.data()}), 1e-9);
    const Pose Mn = M * poseFromXyzRpy({0.3, -0.2, 0.1}, 0.05, -0.1, 0.2);
    expectSameJacobians(backend::relativePoseFactor(Mn, sigma(0.1, 0.01)),
                        backend::relativePoseFactor(Mn, sigma(0.1, 0.01), backend::Differentiation::Numeric),
                        {a.data(), b.data()});
  }
}

TEST(BackendFactors, ScaledOdometryMatchesNumericAndTakesTheScaleToTheTranslationOnly) {
  std::mt19937 rng(6);
  for (int trial = 0; trial < 5; ++trial) {
    const Pose A = randomPose(rng), B = randomPose(rng);
    const backend::PoseBlock a = backend::toPoseBlock(A), b = backend::toPoseBlock(B);
    // The odometry measured the step 3 % short: the estimated scale 1/0.97 explains it.
    Pose M = A.inverse() * B;
    M.translation() *= 0.97;
    const double right = 1.0 / 0.97, one = 1.0;
    EXPECT_LT(residualNorm(backend::scaledOdometryFactor(M, sigma(0.1, 0.01)), {a.data(), b.data(), &right}), 1e-9);
    if (M.translation().norm() > 0.5)
      EXPECT_GT(residualNorm(backend::scaledOdometryFactor(M, sigma(0.1, 0.01)), {a.data(), b.data(), &one}), 0.1);
    // At scale 1 it is the relative pose factor.
    EXPECT_NEAR(residualNorm(backend::scaledOdometryFactor(M, sigma(0.1, 0.01)), {a.data(), b.data(), &one}),
                residualNorm(backend::relativePoseFactor(M, sigma(0.1, 0.01)), {a.data(), b.data()}), 1e-12);
    const double s = 1.02;
    expectSameJacobians(backend::scaledOdometryFactor(M, sigma(0.1, 0.01)),
                        backend::scaledOdometryFactor(M, sigma(0.1, 0.01), backend::Differentiation::Numeric),
                        {a.data(), b.data(), &s});
  }
  const double s = 1.03;
  EXPECT_NEAR(residualNorm(backend::scalePriorFactor(0.02), {&s}), 1.5, 1e-12);
  expectSameJacobians(backend::scalePriorFactor(0.02), backend::scalePriorFactor(0.02, backend::Differentiation::Numeric),
                      {&s});
}

TEST(BackendFactors, PosePriorMatchesNumeric) {
  std::mt19937 rng(2);
  const Pose T = randomPose(rng);
  const backend::PoseBlock t = backend::toPoseBlock(T);
  EXPECT_LT(residualNorm(backend::posePriorFactor(T, sigma(0.01, 0.01)), {t.data()}), 1e-9);
  const Pose M = randomPose(rng);
  expectSameJacobians(backend::posePriorFactor(M, sigma(0.01, 0.02)),
                      backend::posePriorFactor(M, sigma(0.01, 0.02), backend::Differentiation::Numeric), {t.data()});
}

TEST(BackendFactors, GravityHoldsRollAndPitchNotYawNorPosition) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const Pose T = randomPose(rng);
    const Eigen::Quaterniond q(T.linear());
    const backend::PoseBlock t = backend::toPoseBlock(T);
    EXPECT_LT(residualNorm(backend::gravityFactor(q, 0.01), {t.data()}), 1e-9);
    // Another heading and position, the same tilt: still no residual.
    const backend::PoseBlock turned = backend::toPoseBlock(poseFromXyzRpy({5, -3, 2}, 0, 0, 1.3) * T);
    EXPECT_LT(residualNorm(backend::gravityFactor(q, 0.01), {turned.data()}), 1e-9);
    // Tilted by 0.02 rad about a level axis: 2 sin(0.01) / sigma.
    const backend::PoseBlock tilted = backend::toPoseBlock(poseFromXyzRpy({0, 0, 0}, 0.02, 0, 0) * T);
    EXPECT_NEAR(residualNorm(backend::gravityFactor(q, 0.01), {tilted.data()}), 200 * std::sin(0.01), 1e-9);
    expectSameJacobians(backend::gravityFactor(q, 0.01),
                        backend::gravityFactor(q, 0.01, backend::Differentiation::Numeric), {tilted.data()});
  }
}

TEST(BackendFactors, CuboidMatchesNumeric) {
  std::mt19937 rng(3);
  const Pose body = randomPose(rng), box = randomPose(rng, 10);
  const Eigen::Vector3d dims(4.5, 1.8, 1.5);
  const backend::PoseBlock b = backend::toPoseBlock(body), c = backend::toPoseBlock(box);
  const Pose measured = body.inverse() * box;
  EXPECT_LT(residualNorm(backend::cuboidFactor(measured, dims, sigma(0.3, 0.1), Eigen::Vector3d::Constant(0.2)),
                         {b.data(), c.data(), dims.data()}),
            1e-9);
  const Pose noisy = measured * poseFromXyzRpy({0.2, 0.1, -0.1}, 0.02, 0.01, 0.1);
  const Eigen::Vector3d noisy_dims(4.2, 2.0, 1.4);
  expectSameJacobians(backend::cuboidFactor(noisy, noisy_dims, sigma(0.3, 0.1), Eigen::Vector3d::Constant(0.2)),
                      backend::cuboidFactor(noisy, noisy_dims, sigma(0.3, 0.1), Eigen::Vector3d::Constant(0.2),
                                   backend::Differentiation::Numeric),
                      {b.data(), c.data(), dims.data()});
}

TEST(BackendFactors, CylinderMatchesNumeric) {
  std::mt19937 rng(4);
  const Pose body = randomPose(rng);
  const Eigen::Vector3d root(8, 3, -1), axis = Eigen::Vector3d(0.05, -0.02, 1).normalized();
  const double cyl[7] = {root.x(), root.y(), root.z(), axis.x(), axis.y(), axis.z(), 0.3};
  const backend::PoseBlock b = backend::toPoseBlock(body);
  backend::CylinderNoise n;
  n.position_sqrt_info = Eigen::Vector3d(10, 2, 5).asDiagonal();
  const Eigen::Vector3d root_b = body.inverse() * root, axis_b = body.linear().transpose() * axis;
  EXPECT_LT(residualNorm(backend::cylinderFactor(root_b, axis_b, 0.3, n), {b.data(), cyl}), 1e-9);
  // Sliding the measured root along the axis costs only the weak along-axis term.
  const double slid = residualNorm(backend::cylinderFactor(root_b + 1.0 * axis_b, axis_b, 0.3, n), {b.data(), cyl});
  EXPECT_NEAR(slid, 1.0 / n.along_axis_sigma, 1e-9);
  const Eigen::Vector3d noisy_root = root_b + Eigen::Vector3d(0.2, -0.1, 0.5);
  const Eigen::Vector3d noisy_axis = (axis_b + Eigen::Vector3d(0.03, 0.01, 0)).normalized();
  expectSameJacobians(backend::cylinderFactor(noisy_root, noisy_axis, 0.25, n),
                      backend::cylinderFactor(noisy_root, noisy_axis, 0.25, n, backend::Differentiation::Numeric),
                      {b.data(), cyl});
}

TEST(BackendFactors, EllipsoidMatchesNumeric) {
  std::mt19937 rng(5);
  const Pose body = randomPose(rng);
  const Eigen::Vector3d centroid(4, -2, 0.5);
  const backend::PoseBlock b = backend::toPoseBlock(body);
  const Eigen::Vector3d seen = body.inverse() * centroid;
  EXPECT_LT(residualNorm(backend::ellipsoidFactor(seen, 0.1, 0.05), {b.data(), centroid.data()}), 1e-9);
  // One bearing sigma of azimuth error gives a whitened residual of one.
  const Eigen::Vector3d turned = Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitZ()) * seen;
  EXPECT_NEAR(residualNorm(backend::ellipsoidFactor(turned, 0.1, 0.05), {b.data(), centroid.data()}), 1.0, 0.02);
  const Eigen::Vector3d noisy = seen + Eigen::Vector3d(0.3, -0.2, 0.1);
  expectSameJacobians(backend::ellipsoidFactor(noisy, 0.1, 0.05),
                      backend::ellipsoidFactor(noisy, 0.1, 0.05, backend::Differentiation::Numeric),
                      {b.data(), centroid.data()});
}
