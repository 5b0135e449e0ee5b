// spreadLoopError: a new loop's error is spread along it, its older end stays, and closures
// already met stay met.
#include <gtest/gtest.h>

#include "backend/loop_spread.h"

namespace slide {
namespace {

backend::PoseSigma loopSigma() {
  backend::PoseSigma s;
  s << 0.05, 0.05, 0.05, 0.005, 0.005, 0.005;
  return s;
}

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
  const backend::PoseSigma loop = loopSigma();
  const std::vector<Pose> out = backend::spreadLoopError(est, {}, {{0, b, T_a_b}}, loop, backend::LoopSpreadNoise{});
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
  EXPECT_EQ(backend::spreadLoopError(one, {}, {{0, 0, Pose::Identity()}}, s, backend::LoopSpreadNoise{}).size(), 1u);
}

TEST(LoopSpread, KeepsAClosureAlreadyMetWhileClosingANewOne) {
  // Out 60 one-metre steps along x and back along the same line; the estimate's heading drifts
  // 0.2 degrees per step. The return's first half is already tied to the way out (closure
  // 40 -> 80, met by the estimate as it stands: the graph held it); a new closure ties the last
  // key pose to the first.
  std::vector<Pose> truth, est;
  Pose t = Pose::Identity(), e = Pose::Identity();
  for (int i = 0; i < 121; ++i) {
    truth.push_back(t);
    est.push_back(e);
    const double turn = i == 59 ? M_PI : 0.0;
    t = t * poseFromXyzYaw(1, 0, 0, turn);
    e = e * poseFromXyzYaw(1, 0, 0, turn + 0.2 * M_PI / 180);
  }
  const backend::PoseSigma loop = loopSigma();
  const Pose held = est[40].inverse() * est[80];  // what the graph's solution met
  const Pose fresh = truth[0].inverse() * truth[120];
  const std::vector<Pose> out =
      backend::spreadLoopError(est, {}, {{0, 120, fresh}, {40, 80, held}}, loop, backend::LoopSpreadNoise{});
  const double gap_before = ((est[0].inverse() * est[120]).translation() - fresh.translation()).norm();
  const double gap_after = ((out[0].inverse() * out[120]).translation() - fresh.translation()).norm();
  const double held_after = ((out[40].inverse() * out[80]).translation() - held.translation()).norm();
  EXPECT_GT(gap_before, 5.0);
  EXPECT_LT(gap_after, 0.25 * gap_before);
  EXPECT_LT(held_after, 0.5);
  // Without it the same spread bends the held closure open by more.
  const std::vector<Pose> alone = backend::spreadLoopError(est, {}, {{0, 120, fresh}}, loop, backend::LoopSpreadNoise{});
  EXPECT_GT(((alone[40].inverse() * alone[80]).translation() - held.translation()).norm(), 2 * held_after);
}

TEST(LoopSpread, HoldsKeyPosesBeforeTheChainFixed) {
  // A closure from a key pose before the chain (fixed) to its end pulls the chain, never the fixed pose.
  std::vector<Pose> chain;
  for (int i = 0; i < 20; ++i) chain.push_back(poseFromXyzYaw(10 + i, 0.05 * i, 0, 0));
  const std::vector<Pose> fixed{poseFromXyzYaw(0, 0, 0, 0)};
  const backend::PoseSigma loop = loopSigma();
  const Pose T = poseFromXyzYaw(29, 0, 0, 0);  // the chain's end lies on the x axis
  const std::vector<Pose> out = backend::spreadLoopError(chain, fixed, {{-1, 19, T}}, loop, backend::LoopSpreadNoise{});
  EXPECT_LT((out[0].translation() - chain[0].translation()).norm(), 1e-12);
  EXPECT_LT(std::abs(out[19].translation().y()), 0.5 * std::abs(chain[19].translation().y()));
}

}  // namespace
}  // namespace slide
