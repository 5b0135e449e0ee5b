#include "place/alignment.h"

#include <cmath>

namespace slide::place {

namespace {
void fillResiduals(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b, Alignment& al) {
  al.residuals.resize(a.size());
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    al.residuals[i] = (a[i] - al.T_a_b * b[i]).norm();
    sum += al.residuals[i] * al.residuals[i];
  }
  al.rms = a.empty() ? 0 : std::sqrt(sum / a.size());
}
}  // namespace

Alignment alignXyzYaw(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                      const std::vector<double>& weights) {
  Alignment al;
  if (a.size() != b.size() || a.size() < 2 || (!weights.empty() && weights.size() != a.size())) return al;
  double wsum = 0;
  Eigen::Vector3d ca = Eigen::Vector3d::Zero(), cb = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    wsum += w;
    ca += w * a[i];
    cb += w * b[i];
  }
  if (!(wsum > 0)) return al;
  ca /= wsum;
  cb /= wsum;
  double s = 0, c = 0, spread = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    const Eigen::Vector2d pa = (a[i] - ca).head<2>(), pb = (b[i] - cb).head<2>();
    s += w * (pb.x() * pa.y() - pb.y() * pa.x());
    c += w * pb.dot(pa);
    spread += w * pb.squaredNorm();
  }
  if (!(spread > 1e-12 * wsum)) return al;  // every B point at its centroid: yaw undefined
  const double yaw = std::atan2(s, c);
  al.T_a_b = Pose::Identity();
  al.T_a_b.linear() = rotZ(yaw);
  al.T_a_b.translation() = ca - al.T_a_b.linear() * cb;
  al.ok = al.T_a_b.matrix().allFinite();
  fillResiduals(a, b, al);
  return al;
}

Alignment alignXyzYawRobust(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                            double c, int iterations) {
  Alignment al = alignXyzYaw(a, b);
  if (!al.ok) return al;
  std::vector<double> w(a.size());
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      const double r = al.residuals[i] / c;
      w[i] = 1.0 / (1.0 + r * r);
    }
    Alignment next = alignXyzYaw(a, b, w);
    if (!next.ok) break;
    const bool converged = (next.T_a_b.matrix() - al.T_a_b.matrix()).norm() < 1e-10;
    al = std::move(next);
    if (converged) break;
  }
  return al;
}

}  // namespace slide::place
