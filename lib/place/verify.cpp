#include "place/verify.h"

#include <algorithm>
#include <cmath>

#include "place/alignment.h"

namespace slide::place {

std::vector<LandmarkMatch> guidedMatches(const std::vector<Landmark>& a, const LandmarkIndex& index_a,
                                         const std::vector<Landmark>& b, const Pose& T_a_b,
                                         const VerifyParams& params) {
  struct Cand {
    double d;
    std::size_t ia, ib;
  };
  std::vector<Cand> cands;
  const double reach = std::hypot(params.match_radius, params.match_height);  // the box's corner
  for (std::size_t j = 0; j < b.size(); ++j) {
    const Eigen::Vector3d q = T_a_b * b[j].p;
    index_a.forEachWithin(q, reach, b[j].class_id, [&](std::size_t i) {
      const double d = (a[i].p - q).head<2>().norm();
      if (d <= params.match_radius && std::abs(a[i].p.z() - q.z()) <= params.match_height &&
          sizesAgree(a[i].size, b[j].size, params.size_tolerance))
        cands.push_back({d, i, j});
    });
  }
  std::sort(cands.begin(), cands.end(), [](const Cand& x, const Cand& y) {
    return x.d < y.d || (x.d == y.d && (x.ia < y.ia || (x.ia == y.ia && x.ib < y.ib)));
  });
  std::vector<char> used_a(a.size(), 0), used_b(b.size(), 0);
  std::vector<LandmarkMatch> out;
  for (const Cand& c : cands) {
    if (used_a[c.ia] || used_b[c.ib]) continue;
    used_a[c.ia] = used_b[c.ib] = 1;
    out.push_back({c.ia, c.ib});
  }
  std::sort(out.begin(), out.end(), [](const LandmarkMatch& x, const LandmarkMatch& y) { return x.b < y.b; });
  return out;
}

namespace {
// Coverage radius of a map: three times its median landmark spacing, at least four match radii.
double coverageRadius(const LandmarkIndex& index, double match_radius) {
  return std::max(3.0 * index.medianSpacing(), 4.0 * match_radius);
}
}  // namespace

Overlap overlapOf(const std::vector<Landmark>& a, const LandmarkIndex& index_a, const std::vector<Landmark>& b,
                  const Pose& T_a_b, double match_radius) {
  Overlap o;
  const double R = coverageRadius(index_a, match_radius);
  const double ratio = (match_radius * match_radius) / (R * R);
  for (const Landmark& l : b) {
    const Eigen::Vector3d q = T_a_b * l.p;
    if (index_a.nearest(q, LandmarkIndex::kAnyClass).second > R) continue;
    ++o.covered;
    // Local density of A's landmarks of this class around q, times the match disc.
    const double n = static_cast<double>(index_a.countWithin(q, R, l.class_id));
    o.chance += std::min(1.0, n * ratio);
  }
  return o;
}

std::size_t coveredBy(const std::vector<Landmark>& pts, const Pose& T, const LandmarkIndex& index, double match_radius) {
  const double R = coverageRadius(index, match_radius);
  std::size_t n = 0;
  for (const Landmark& l : pts) n += index.nearest(T * l.p, LandmarkIndex::kAnyClass).second <= R;
  return n;
}

void refineAndDecide(const std::vector<Landmark>& a, const LandmarkIndex& index_a, const std::vector<Landmark>& b,
                     const LandmarkIndex& index_b, const Pose& hypothesis, const VerifyParams& params,
                     PlaceResult& out) {
  out.found = false;
  Pose T = hypothesis;
  std::vector<LandmarkMatch> matches;
  double rms = 0;
  for (int round = 0; round < std::max(1, params.rounds); ++round) {
    matches = guidedMatches(a, index_a, b, T, params);
    if (matches.size() < 2) break;
    std::vector<Eigen::Vector3d> pa, pb;
    for (const LandmarkMatch& m : matches) {
      pa.push_back(a[m.a].p);
      pb.push_back(b[m.b].p);
    }
    const Alignment al = alignXyzYawRobust(pa, pb, params.robust_scale);
    if (!al.ok) break;
    T = al.T_a_b;
    rms = al.rms;
  }
  matches = guidedMatches(a, index_a, b, T, params);
  {
    std::vector<Eigen::Vector3d> pa, pb;
    for (const LandmarkMatch& m : matches) {
      pa.push_back(a[m.a].p);
      pb.push_back(b[m.b].p);
    }
    double sum = 0, support = 0;
    const double r2 = params.match_radius * params.match_radius;
    for (std::size_t i = 0; i < pa.size(); ++i) {
      const Eigen::Vector3d e = pa[i] - T * pb[i];
      sum += e.squaredNorm();
      support += std::max(0.0, 1.0 - e.head<2>().squaredNorm() / r2);
    }
    rms = pa.empty() ? 0 : std::sqrt(sum / pa.size());
    out.support = support;
  }
  out.T_a_b = T;
  out.inliers = matches;
  out.residual_rms = rms;
  // How well the matches fix the yaw: the horizontal residual per axis over the root of the matched
  // landmarks' squared distances from their centroid (a least-squares rotation's standard error).
  double yaw_sigma_deg = 0;
  if (matches.size() >= 2) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const LandmarkMatch& m : matches) c += b[m.b].p.head<2>() / static_cast<double>(matches.size());
    double spread = 0, res2 = 0;
    for (const LandmarkMatch& m : matches) {
      spread += (b[m.b].p.head<2>() - c).squaredNorm();
      res2 += (a[m.a].p.head<2>() - (T * b[m.b].p).head<2>()).squaredNorm();
    }
    const double per_axis = std::sqrt(res2 / (2.0 * static_cast<double>(matches.size())));
    yaw_sigma_deg = per_axis / std::sqrt(std::max(spread, 1e-12)) * 180.0 / M_PI;
  }
  const Overlap ov = overlapOf(a, index_a, b, T, params.match_radius);
  out.chance_inliers = ov.chance;
  out.covered = ov.covered;
  const double n = static_cast<double>(matches.size());
  const bool enough = matches.size() >= params.min_inliers && n >= ov.chance + params.significance * std::sqrt(ov.chance);
  // The overlap as the sparser map holds it; A's side is counted only when B's would reject.
  std::size_t sparser = ov.covered, covered_a = 0;
  if (enough && n < params.min_inlier_ratio * static_cast<double>(ov.covered)) {
    covered_a = coveredBy(a, T.inverse(), index_b, params.match_radius);
    sparser = std::min(sparser, covered_a);
  }
  char buf[256];
  if (matches.size() < params.min_inliers) {
    std::snprintf(buf, sizeof buf, "best hypothesis has %zu inliers, fewer than the minimum %zu", matches.size(),
                  params.min_inliers);
  } else if (n < ov.chance + params.significance * std::sqrt(ov.chance)) {
    std::snprintf(buf, sizeof buf, "best hypothesis has %zu inliers, not significant against %.1f expected by chance",
                  matches.size(), ov.chance);
  } else if (n < params.min_inlier_ratio * static_cast<double>(sparser)) {
    std::snprintf(buf, sizeof buf,
                  "best hypothesis matches %zu of %zu overlapping landmarks (%zu of B's, %zu of A's), below the ratio %.2f",
                  matches.size(), sparser, ov.covered, covered_a, params.min_inlier_ratio);
  } else if (yaw_sigma_deg > params.max_yaw_sigma_deg) {
    std::snprintf(buf, sizeof buf, "best hypothesis's %zu matches fix its yaw only to %.1f deg (limit %.1f)", matches.size(),
                  yaw_sigma_deg, params.max_yaw_sigma_deg);
  } else {
    out.found = true;
    out.reason.clear();
    return;
  }
  out.reason = buf;
}

double strengthOf(const PlaceResult& r, bool by_fit) {
  const double n = by_fit ? r.support : static_cast<double>(r.inliers.size());
  return n * n / static_cast<double>(std::max<std::size_t>(1, r.covered));
}

bool fitDecides(const PlaceResult& best, const VerifyParams& params) {
  const double n = static_cast<double>(best.inliers.size());
  if (n < 1) return false;
  // 1 - u for u uniform on [0, 1): mean 1/2, standard deviation 1 / sqrt(12).
  return best.support / n >= 0.5 + params.significance / std::sqrt(12.0 * n);
}

const PlaceResult* rivalOf(const PlaceResult& best, const std::vector<PlaceResult>& hypotheses,
                           const std::vector<Landmark>& b, const VerifyParams& params) {
  std::vector<std::pair<std::size_t, std::size_t>> mine;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const LandmarkMatch& m : best.inliers) {
    mine.emplace_back(m.a, m.b);
    c += b[m.b].p / static_cast<double>(best.inliers.size());
  }
  std::sort(mine.begin(), mine.end());
  const double yaw = yawOf(best.T_a_b.linear());
  const bool by_fit = fitDecides(best, params);
  const PlaceResult* rival = nullptr;
  for (const PlaceResult& h : hypotheses) {
    std::size_t common = 0;
    for (const LandmarkMatch& m : h.inliers) common += std::binary_search(mine.begin(), mine.end(), std::pair{m.a, m.b});
    const bool elsewhere = (h.T_a_b * c - best.T_a_b * c).head<2>().norm() > params.rival_separation ||
                           std::abs(wrapAngle(yawOf(h.T_a_b.linear()) - yaw)) > 5.0 * M_PI / 180.0;
    if (2 * common < h.inliers.size() && elsewhere && (!rival || strengthOf(h, by_fit) > strengthOf(*rival, by_fit)))
      rival = &h;
  }
  return rival;
}

bool standsAgainstRival(const PlaceResult* rival, const VerifyParams& params, PlaceResult& best) {
  if (!best.found || !rival) return best.found;
  const bool by_fit = fitDecides(best, params);
  const double ratio = strengthOf(best, by_fit) / std::max(1e-12, strengthOf(*rival, by_fit));
  if (ratio >= params.rival_ratio) return best.found;
  best.found = false;
  best.ambiguous = true;
  char buf[240];
  std::snprintf(buf, sizeof buf,
                "ambiguous: best hypothesis matches %zu of %zu covered landmarks, another alignment %zu of %zu (strength "
                "ratio %.2f%s, below %.2f)",
                best.inliers.size(), best.covered, rival->inliers.size(), rival->covered, ratio,
                by_fit ? " by fit" : "", params.rival_ratio);
  best.reason = buf;
  return false;
}

}  // namespace slide::place
