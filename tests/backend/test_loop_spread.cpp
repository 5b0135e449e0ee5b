// spreadLoopError: the loop's error is spread along it, its older end stays.
#include <gtest/gtest.h>

#include "backend/loop_spread.h"

namespace slide {
namespace {

TEST(LoopSpread, ClosesTheLoopAndKeepsItsStart) {
  // A square of 40 one-metre steps whose estimate turns slightly too little at each step.
  std::vector<Pose> truth, est;
  Pose t = Pose::Identity(), e = Pose::Identity();
  for (int i = 0; i < 40; ++i) {
    truth.push_back(t);
    est.push_back(e);
    const double turn = (i % 10 == 9) ? M_PI / 2 : 0.0;
    t = t * poseFromXyzYaw(1, 0, 0, turn);
    e = e * poseFromXyzYaw(1, 0, 0, turn * 0.97);
  }
  const int b = 39;
  const Pose T_a_b = truth[0].inverse() * truth[b];
  const double before = (est[b].translation() - truth[b].translation()).norm();
  backend::PoseSigma loop;
  loop << 0.05, 0.05, 0.05, 0.005, 0.005, 0.005;
  const std::vector<Pose> out = backend::spreadLoopError(est, b, T_a_b, loop, backend::LoopSpreadNoise{});
  ASSERT_EQ(out.size(), est.size());
  EXPECT_LT((out[0].translation() - est[0].translation()).norm(), 1e-12);
  const double after = ((out[0].inverse() * out[b]).translation() - T_a_b.translation()).norm();
  // Weighted against the chain's own sigmas the loop is not met exactly, but most of the gap closes.
  EXPECT_GT(before, 1.0);
  EXPECT_LT(after, 0.25 * before);
  // The correction grows along the loop instead of landing on the last pose alone.
  const double mid = (out[20].translation() - est[20].translation()).norm();
  EXPECT_GT(mid, 0.1 * before);
  EXPECT_LT(mid, before);
}

TEST(LoopSpread, LeavesPosesAloneWithoutALoop) {
  const std::vector<Pose> one{Pose::Identity()};
  backend::PoseSigma s = backend::PoseSigma::Constant(0.1);
  EXPECT_EQ(backend::spreadLoopError(one, 0, Pose::Identity(), s, backend::LoopSpreadNoise{}).size(), 1u);
}

}  // namespace
}  // namespace slide
