// Pose interpolation (interpolatePose, poseAtTime) and deskew against analytic motion with
// roll and pitch on a curved (screw) path, not only the planar yaw motion of the bag tests.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geometry/deskew.h"
#include "geometry/stamped_pose.h"

using namespace slide;

namespace {
// A constant body twist: translation and rotation about a tilted axis, so the path is a helix
// and roll, pitch and yaw all change. T_odom_body(t) = exp(t xi), exact at any t.
Vector6d twist() {
  Vector6d xi;
  xi << 2.0, 0.3, 0.2, 0.4, -0.3, 0.9;  // m/s, rad/s
  return xi;
}
Pose motion(double t) { return expSE3(t * twist()); }

std::vector<StampedPose> sampled(double t0, double t1, double dt) {
  std::vector<StampedPose> traj;
  for (double t = t0; t <= t1 + 1e-9; t += dt) traj.push_back({t, motion(t)});
  return traj;
}

double rotationError(const Pose& a, const Pose& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
}
}  // namespace

TEST(InterpolatePose, EndsAreExactAndRotationSlerpsAboutATiltedAxis) {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  Pose a = Pose::Identity(), b = Pose::Identity();
  a.linear() = Eigen::AngleAxisd(0.2, axis).toRotationMatrix();
  b.linear() = Eigen::AngleAxisd(1.4, axis).toRotationMatrix();
  a.translation() << 1, 2, 3;
  b.translation() << 3, -2, 4;
  EXPECT_TRUE(interpolatePose(a, b, 0).isApprox(a, 1e-12));
  EXPECT_TRUE(interpolatePose(a, b, 1).isApprox(b, 1e-12));
  const Pose q = interpolatePose(a, b, 0.25);
  EXPECT_LT(Eigen::AngleAxisd(Eigen::AngleAxisd(0.5, axis).toRotationMatrix().transpose() * q.linear()).angle(), 1e-12);
  EXPECT_TRUE(q.translation().isApprox(Eigen::Vector3d(1.5, 1, 3.25), 1e-12));
}

TEST(InterpolatePose, TakesTheShortWayAcrossPlusMinusPi) {
  const Pose a = poseFromXyzRpy({0, 0, 0}, 0.1, -0.2, 3.0), b = poseFromXyzRpy({0, 0, 0}, 0.1, -0.2, -3.0);
  const Pose m = interpolatePose(a, b, 0.5);
  EXPECT_LT(rotationError(a, m), 0.2);  // 0.14 rad from each end, not half-way round the other side
  EXPECT_LT(rotationError(b, m), 0.2);
  EXPECT_NEAR(std::abs(yawOf(m.linear())), M_PI, 0.05);
}

TEST(PoseAtTime, InterpolatesScrewMotionAndRefusesOutsideTheSpanOrAcrossAGap) {
  std::vector<StampedPose> traj = sampled(10.0, 11.0, 0.01);  // 100 Hz with roll, pitch and yaw moving
  Pose T;
  for (double t : {10.0, 10.003, 10.5, 10.777, 11.0}) {
    ASSERT_EQ(poseAtTime(traj, t, 0.05, T), PoseMiss::None) << t;
    // Slerp is exact for a fixed rotation axis; the translation's chord is 2.5e-5 m off the helix.
    EXPECT_LT(rotationError(T, motion(t)), 1e-9) << t;
    EXPECT_LT((T.translation() - motion(t).translation()).norm(), 5e-5) << t;
  }
  EXPECT_TRUE(traj[37].pose.isApprox(motion(10.37), 1e-12));
  ASSERT_EQ(poseAtTime(traj, traj[37].t + 1e-6, 0.05, T), PoseMiss::None);  // within kSameTimeS: the sample
  EXPECT_EQ(T.matrix(), traj[37].pose.matrix());
  EXPECT_EQ(poseAtTime(traj, 9.999, 0.05, T), PoseMiss::OutsideSpan);
  EXPECT_EQ(poseAtTime(traj, 11.001, 0.05, T), PoseMiss::OutsideSpan);
  EXPECT_EQ(poseAtTime(traj, std::numeric_limits<double>::quiet_NaN(), 0.05, T), PoseMiss::OutsideSpan);
  EXPECT_EQ(poseAtTime({}, 10.5, 0.05, T), PoseMiss::OutsideSpan);
  EXPECT_EQ(poseAtTime(traj, 10.505, 0.005, T), PoseMiss::Gap);  // samples 0.01 s apart, limit 0.005 s
  traj.erase(traj.begin() + 40, traj.begin() + 60);             // nothing from 10.40 to 10.59
  EXPECT_EQ(poseAtTime(traj, 10.5, 0.05, T), PoseMiss::Gap);
  EXPECT_EQ(poseAtTime(traj, 10.5, 0.25, T), PoseMiss::None);   // a larger limit bridges it
}

TEST(Deskew, SweepOnAScrewPathWithRollAndPitchLandsOnTheWorld) {
  // A static world of points at 5-40 m, each measured from the body at its own time over a
  // 0.1 s sweep; the odometry is sampled at 200 Hz and looked up by poseAtTime.
  const std::vector<StampedPose> traj = sampled(0.0, 1.0, 0.005);
  const PoseLookup at = [&](double t, Pose& T) { return poseAtTime(traj, t, 0.02, T); };
  const double t_ref = 0.6;
  std::vector<Eigen::Vector3f> xyz;
  std::vector<double> dt;
  std::vector<Eigen::Vector3d> world;
  for (int i = 0; i < 2000; ++i) {
    const double az = 2 * M_PI * i / 2000.0, el = 0.3 * std::sin(7.0 * az), r = 5.0 + 35.0 * (i % 7) / 6.0;
    const Eigen::Vector3d w = motion(t_ref) * Eigen::Vector3d(r * std::cos(az) * std::cos(el), r * std::sin(az) * std::cos(el),
                                                              r * std::sin(el));
    const double d = -0.1 + 0.1 * i / 2000.0;  // Velodyne-style: times before the stamp
    world.push_back(w);
    dt.push_back(d);
    xyz.push_back((motion(t_ref + d).inverse() * w).cast<float>());
  }
  auto worst = [&](const std::vector<Eigen::Vector3f>& pts) {
    double e = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) e = std::max(e, (motion(t_ref) * pts[i].cast<double>() - world[i]).norm());
    return e;
  };
  EXPECT_GT(worst(xyz), 1.0);  // smeared by metres at 40 m and ~1 rad/s
  const std::vector<uint8_t> ok = deskewSweep(xyz, dt, t_ref, at);
  EXPECT_EQ(std::count(ok.begin(), ok.end(), 1), 2000);
  EXPECT_LT(worst(xyz), 5e-3);  // grid of 0.1 ms: at most 40 m x 1.05 rad/s x 0.05 ms, plus float
}

TEST(Deskew, PointsWithoutAPoseAreFlaggedAndLeftAlone) {
  const std::vector<StampedPose> traj = sampled(0.0, 0.55, 0.005);
  const PoseLookup at = [&](double t, Pose& T) { return poseAtTime(traj, t, 0.02, T); };
  std::vector<Eigen::Vector3f> xyz(3, Eigen::Vector3f(1, 2, 3));
  const std::vector<uint8_t> ok = deskewSweep(xyz, {-0.05, 0.0, 0.1}, 0.5, at);  // the last at 0.6 s: no odometry
  EXPECT_EQ(ok, (std::vector<uint8_t>{1, 1, 0}));
  EXPECT_EQ(xyz[2], Eigen::Vector3f(1, 2, 3));
  EXPECT_NE(xyz[0], Eigen::Vector3f(1, 2, 3));
  EXPECT_EQ(deskewSweep(xyz, {0, 0, 0}, 0.7, at), (std::vector<uint8_t>{0, 0, 0}));  // no pose at the stamp
  EXPECT_THROW(deskewSweep(xyz, {0, 0}, 0.5, at), std::invalid_argument);
}
