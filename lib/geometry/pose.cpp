#include "geometry/pose.h"

#include <algorithm>
#include <cmath>

namespace slide {

double wrapAngle(double a) {
  a = std::fmod(a + M_PI, 2.0 * M_PI);
  if (a <= 0.0) a += 2.0 * M_PI;
  return a - M_PI;
}

Eigen::Matrix3d rotZ(double yaw) { return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

double yawOf(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

Pose poseFromXyzYaw(double x, double y, double z, double yaw) {
  Pose T = Pose::Identity();
  T.linear() = rotZ(yaw);
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

Pose poseFromXyzYaw(const Eigen::Vector4d& v) { return poseFromXyzYaw(v[0], v[1], v[2], v[3]); }

Eigen::Vector4d xyzYawOf(const Pose& T) {
  const Eigen::Vector3d t = T.translation();
  return {t.x(), t.y(), t.z(), yawOf(T.linear())};
}

Eigen::Vector3d rpyOf(const Eigen::Matrix3d& R) {
  return {std::atan2(R(2, 1), R(2, 2)), std::asin(std::clamp(-R(2, 0), -1.0, 1.0)), yawOf(R)};
}

Pose poseFromXyzRpy(const Eigen::Vector3d& t, double roll, double pitch, double yaw) {
  Pose T = Pose::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = t;
  return T;
}

namespace {
Eigen::Matrix3d hat(const Eigen::Vector3d& w) {
  Eigen::Matrix3d W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return W;
}

// Left Jacobian of SO(3) and its inverse.
Eigen::Matrix3d leftJacobian(const Eigen::Vector3d& phi) {
  const double th = phi.norm();
  const Eigen::Matrix3d W = hat(phi);
  if (th < 1e-8) return Eigen::Matrix3d::Identity() + 0.5 * W;
  return Eigen::Matrix3d::Identity() + (1 - std::cos(th)) / (th * th) * W + (th - std::sin(th)) / (th * th * th) * W * W;
}

Eigen::Matrix3d leftJacobianInverse(const Eigen::Vector3d& phi) {
  const double th = phi.norm();
  const Eigen::Matrix3d W = hat(phi);
  if (th < 1e-8) return Eigen::Matrix3d::Identity() - 0.5 * W;
  const double c = 1.0 / (th * th) - (1 + std::cos(th)) / (2 * th * std::sin(th));
  return Eigen::Matrix3d::Identity() - 0.5 * W + c * W * W;
}
}  // namespace

Pose expSE3(const Vector6d& xi) {
  const Eigen::Vector3d rho = xi.head<3>(), phi = xi.tail<3>();
  Pose T = Pose::Identity();
  const double th = phi.norm();
  T.linear() = th < 1e-12 ? Eigen::Matrix3d::Identity() : Eigen::AngleAxisd(th, phi / th).toRotationMatrix();
  T.translation() = leftJacobian(phi) * rho;
  return T;
}

Vector6d logSE3(const Pose& T) {
  const Eigen::AngleAxisd aa(T.linear());
  const Eigen::Vector3d phi = aa.angle() * aa.axis();
  Vector6d xi;
  xi.head<3>() = leftJacobianInverse(phi) * T.translation();
  xi.tail<3>() = phi;
  return xi;
}

Pose poseFromPositionQuaternion(const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
  Pose T = Pose::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = p;
  return T;
}

Pose interpolatePose(const Pose& a, const Pose& b, double s) {
  const Eigen::Quaterniond qa(a.linear()), qb(b.linear());
  Pose T = Pose::Identity();
  T.linear() = qa.slerp(s, qb).normalized().toRotationMatrix();
  T.translation() = (1.0 - s) * a.translation() + s * b.translation();
  return T;
}

}  // namespace slide
