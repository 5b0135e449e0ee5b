#pragma once
// Cost functions of the back-end factor graph. Each factory returns a new ceres::CostFunction
// (the caller owns it) built from a Ceres-style functor defined in its own .cpp, with
// automatic differentiation, or numeric differentiation for checking Jacobians.
// Residuals are whitened (divided by their standard deviations).
//
// Parameter blocks: poses as in pose_block.h ([t, q], 7 values); cuboid landmark pose (7)
// and dims (3); cylinder landmark [root(3), unit axis(3), radius(1)]; ellipsoid centroid (3);
// a robot's odometry scale (1).
#include "geometry/pose.h"

namespace ceres {
class CostFunction;
class Manifold;
}  // namespace ceres

namespace slide::backend {

enum class Differentiation { Automatic, Numeric };

// Standard deviations of a 6-DoF pose error, ordered (x, y, z, roll, pitch, yaw) as in
// keypose_bundle_t: translation in metres, rotation in radians.
using PoseSigma = Vector6d;

// Between two poses A and B (blocks: A, B): log(M^-1 A^-1 B). Odometry between consecutive
// key poses and intra-robot loop closures both use it. 6 residuals.
ceres::CostFunction* relativePoseFactor(const Pose& measured_a_b, const PoseSigma& sigma,
                                        Differentiation d = Differentiation::Automatic);

// Odometry between consecutive key poses of a robot whose odometry scale is estimated (blocks:
// A, B, the robot's scale s, one value): log(M_s^-1 A^-1 B), M_s the measurement with its
// translation times s. 6 residuals.
ceres::CostFunction* scaledOdometryFactor(const Pose& measured_a_b, const PoseSigma& sigma,
                                          Differentiation d = Differentiation::Automatic);

// Prior on a robot's odometry scale (block: s): (s - 1) / sigma. 1 residual.
ceres::CostFunction* scalePriorFactor(double sigma, Differentiation d = Differentiation::Automatic);

// Prior on one pose (block: pose): log(M^-1 T). 6 residuals.
ceres::CostFunction* posePriorFactor(const Pose& measured, const PoseSigma& sigma,
                                     Differentiation d = Differentiation::Automatic);

// Roll and pitch of one pose (block: pose) from the odometry's attitude, which an IMU keeps
// gravity-aligned without drift (every robot frame is gravity-aligned): the up direction in
// the body frame, measured against the pose's (their difference). Yaw is free. 3 residuals.
ceres::CostFunction* gravityFactor(const Eigen::Quaterniond& measured, double sigma,
                                   Differentiation d = Differentiation::Automatic);

// Cuboid seen from a key pose (blocks: key pose, cuboid pose, cuboid dims): SE(3) log error
// between predicted and measured cuboid pose in the body frame, then the dims difference.
// 9 residuals.
ceres::CostFunction* cuboidFactor(const Pose& measured_in_body, const Eigen::Vector3d& measured_dims,
                                  const PoseSigma& pose_sigma, const Eigen::Vector3d& dims_sigma,
                                  Differentiation d = Differentiation::Automatic);

// Noise of a cylinder observation. position_sqrt_info whitens a position error in the body
// frame (e.g. radial and tangential from a range-bearing sensor); the root's offset along
// the axis is weakly constrained (views cover different heights).
struct CylinderNoise {
  Eigen::Matrix3d position_sqrt_info = Eigen::Matrix3d::Identity();
  double along_axis_sigma = 2.0;
  double axis_sigma = 0.1;
  double radius_sigma = 0.05;
};

// Cylinder seen from a key pose (blocks: key pose, cylinder): the measured root's offset from
// the predicted axis line (whitened, 3), its offset along the axis (1), axis direction
// difference (3), radius difference (1). 8 residuals.
ceres::CostFunction* cylinderFactor(const Eigen::Vector3d& root_in_body, const Eigen::Vector3d& axis_in_body,
                                    double radius, const CylinderNoise& noise,
                                    Differentiation d = Differentiation::Automatic);

// Ellipsoid centroid seen from a key pose (blocks: key pose, centroid): range, azimuth and
// elevation differences. 3 residuals. (Radius and height are not optimized: the graph keeps
// an exponential moving average of the measured ones.)
ceres::CostFunction* ellipsoidFactor(const Eigen::Vector3d& centroid_in_body, double range_sigma,
                                     double bearing_sigma, Differentiation d = Differentiation::Automatic);

// Manifolds of the blocks above (caller owns): pose [t, q] and cylinder [root, axis, radius].
ceres::Manifold* newPoseManifold();
ceres::Manifold* newCylinderManifold();

}  // namespace slide::backend
