#include "place/map_perturb.h"

#include <cmath>

namespace slide::place {

std::vector<Landmark> perturbedCopy(const std::vector<Landmark>& a, const Pose& T_a_b, const PerturbParams& p,
                                    std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Pose T_b_a = T_a_b.inverse();
  std::vector<Landmark> out;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (u(rng) < p.drop_fraction) continue;
    Landmark l = a[i];
    l.p = T_b_a * a[i].p + p.position_sigma * Eigen::Vector3d(n(rng), n(rng), n(rng));
    if (p.size_sigma > 0 && !l.size.isZero())
      for (int k = 0; k < 3; ++k) l.size[k] = std::max(0.01, l.size[k] + p.size_sigma * n(rng));
    out.push_back(l);
  }
  return out;
}

}  // namespace slide::place
