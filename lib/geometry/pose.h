#pragma once
// Rigid-body helpers. Poses are Eigen::Isometry3d; T_a_b maps points of frame b into frame a.
// Roll and pitch come from the IMU and are trusted; 4-DoF helpers handle x, y, z, yaw.
// Vocabulary: in namespace slide itself, not slide::geometry, as every area uses it (README).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace slide {

using Pose = Eigen::Isometry3d;
using Vector6d = Eigen::Matrix<double, 6, 1>;

// Angle wrapped into (-pi, pi].
double wrapAngle(double a);

// Rotation about z by yaw (radians).
Eigen::Matrix3d rotZ(double yaw);

// Yaw of a rotation (ZYX convention: R = Rz(yaw) * Ry(pitch) * Rx(roll)).
double yawOf(const Eigen::Matrix3d& R);

// Pose from x, y, z and yaw; roll and pitch zero.
Pose poseFromXyzYaw(double x, double y, double z, double yaw);
Pose poseFromXyzYaw(const Eigen::Vector4d& xyz_yaw);

// (x, y, z, yaw) of a pose; roll and pitch are dropped.
Eigen::Vector4d xyzYawOf(const Pose& T);

// Pose from translation and ZYX Euler angles (roll, pitch, yaw).
Pose poseFromXyzRpy(const Eigen::Vector3d& t, double roll, double pitch, double yaw);
// ZYX Euler angles (roll, pitch, yaw) of a rotation: the inverse of poseFromXyzRpy.
Eigen::Vector3d rpyOf(const Eigen::Matrix3d& R);

// SE(3) exponential and logarithm; tangent ordered (translation rho, rotation phi).
Pose expSE3(const Vector6d& xi);
Vector6d logSE3(const Pose& T);

// Pose from position and quaternion (w, x, y, z); the quaternion is normalized.
Pose poseFromPositionQuaternion(const Eigen::Vector3d& p, const Eigen::Quaterniond& q);

// Pose between a (s = 0) and b (s = 1): linear in translation, slerp in rotation.
Pose interpolatePose(const Pose& a, const Pose& b, double s);

}  // namespace slide
