#include "eval/alignment.h"

#include <Eigen/SVD>
#include <cmath>
#include <stdexcept>

namespace slide::eval {

TrajectoryAlignment parseAlignment(const std::string& name) {
  if (name == "none") return TrajectoryAlignment::None;
  if (name == "se3") return TrajectoryAlignment::Se3;
  if (name == "sim3") return TrajectoryAlignment::Sim3;
  if (name == "yaw") return TrajectoryAlignment::Yaw4Dof;
  throw std::invalid_argument("alignment must be none, se3, sim3 or yaw, got '" + name + "'");
}

const char* alignmentName(TrajectoryAlignment a) {
  switch (a) {
    case TrajectoryAlignment::None: return "none";
    case TrajectoryAlignment::Se3: return "se3";
    case TrajectoryAlignment::Sim3: return "sim3";
    case TrajectoryAlignment::Yaw4Dof: return "yaw";
  }
  return "?";
}

AlignmentResult align(const std::vector<Eigen::Vector3d>& est, const std::vector<Eigen::Vector3d>& ref,
                      TrajectoryAlignment mode) {
  if (est.size() != ref.size()) throw std::invalid_argument("align: point sets differ in size");
  AlignmentResult out;
  if (mode == TrajectoryAlignment::None || est.empty()) return out;
  const double n = static_cast<double>(est.size());
  Eigen::Vector3d mu_e = Eigen::Vector3d::Zero(), mu_r = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < est.size(); ++i) {
    mu_e += est[i];
    mu_r += ref[i];
  }
  mu_e /= n;
  mu_r /= n;

  if (mode == TrajectoryAlignment::Yaw4Dof) {
    // Rotation about z only: maximise sum of in-plane cross/dot terms.
    double s_cos = 0, s_sin = 0;
    for (std::size_t i = 0; i < est.size(); ++i) {
      const Eigen::Vector3d a = est[i] - mu_e, b = ref[i] - mu_r;
      s_cos += a.x() * b.x() + a.y() * b.y();
      s_sin += a.x() * b.y() - a.y() * b.x();
    }
    const double yaw = std::atan2(s_sin, s_cos);
    out.T.linear() = rotZ(yaw);
    out.T.translation() = mu_r - out.T.linear() * mu_e;
    return out;
  }

  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  double var_e = 0;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const Eigen::Vector3d a = est[i] - mu_e, b = ref[i] - mu_r;
    cov += b * a.transpose();
    var_e += a.squaredNorm();
  }
  cov /= n;
  var_e /= n;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) S(2, 2) = -1;
  const Eigen::Matrix3d R = svd.matrixU() * S * svd.matrixV().transpose();
  if (mode == TrajectoryAlignment::Sim3 && var_e > 0) out.scale = (svd.singularValues().asDiagonal() * S).trace() / var_e;
  out.T.linear() = R;
  out.T.translation() = mu_r - out.scale * R * mu_e;
  return out;
}

}  // namespace slide::eval
