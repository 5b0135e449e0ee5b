#pragma once
// Templated SE(3) helpers for Ceres cost functors (double or ceres::Jet). Private to the
// factor sources of lib/backend: include only from .cpp files. Pose blocks are laid out as
// in pose_block.h: [tx, ty, tz, qx, qy, qz, qw].
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace slide::backend::jet {

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using Vec6 = Eigen::Matrix<T, 6, 1>;

template <typename T>
Eigen::Map<const Vec3<T>> translationOf(const T* pose) {
  return Eigen::Map<const Vec3<T>>(pose);
}
template <typename T>
Eigen::Map<const Eigen::Quaternion<T>> rotationOf(const T* pose) {
  return Eigen::Map<const Eigen::Quaternion<T>>(pose + 3);
}

// SE(3) logarithm (rho, phi) of the rigid transform (q, t); q must be close to unit length.
template <typename T>
Vec6<T> logSE3(const Eigen::Quaternion<T>& q, const Vec3<T>& t) {
  const T wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
  Vec3<T> phi;
  ceres::QuaternionToAngleAxis(wxyz, phi.data());
  const T theta2 = phi.squaredNorm();
  Eigen::Matrix<T, 3, 3> Phi;
  Phi << T(0), -phi.z(), phi.y(), phi.z(), T(0), -phi.x(), -phi.y(), phi.x(), T(0);
  // V^-1 = I - Phi/2 + c * Phi^2, c = (1 - theta sin(theta) / (2 (1 - cos(theta)))) / theta^2.
  T c;
  if (theta2 < T(1e-8)) {
    c = T(1.0 / 12.0) + theta2 / T(720.0);
  } else {
    const T theta = sqrt(theta2);
    c = (T(1) - theta * sin(theta) / (T(2) * (T(1) - cos(theta)))) / theta2;
  }
  const Eigen::Matrix<T, 3, 3> Vinv = Eigen::Matrix<T, 3, 3>::Identity() - T(0.5) * Phi + c * Phi * Phi;
  Vec6<T> xi;
  xi.template head<3>() = Vinv * t;
  xi.template tail<3>() = phi;
  return xi;
}

// log(M^-1 * A^-1 * B) for poses A, B (blocks) and a constant measurement M (q_m, t_m):
// zero when B seen from A equals M.
// The measured translation may itself depend on a variable (an odometry scale): S is double or T.
template <typename T, typename S>
Vec6<T> relativePoseError(const T* a, const T* b, const Eigen::Quaterniond& q_m, const Eigen::Matrix<S, 3, 1>& t_m) {
  const Eigen::Quaternion<T> qa_inv = rotationOf(a).conjugate();
  const Eigen::Quaternion<T> q_ab = qa_inv * rotationOf(b);
  const Vec3<T> t_ab = qa_inv * (translationOf(b) - translationOf(a));
  const Eigen::Quaternion<T> qm_inv = q_m.conjugate().cast<T>();
  const Eigen::Quaternion<T> q_err = qm_inv * q_ab;
  const Vec3<T> t_err = qm_inv * (t_ab - t_m.template cast<T>());
  return logSE3(q_err, t_err);
}

// A world point seen from the body frame of pose block `pose`.
template <typename T>
Vec3<T> toBody(const T* pose, const Vec3<T>& p_world) {
  return rotationOf(pose).conjugate() * (p_world - translationOf(pose));
}

}  // namespace slide::backend::jet
