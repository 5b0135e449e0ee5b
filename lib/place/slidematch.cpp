#include "place/slidematch.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "place/class_grid.h"

namespace slide {

namespace {
using Clock = std::chrono::steady_clock;

struct Candidate {
  double score = -1;
  double yaw = 0, tx = 0, ty = 0;
};

// Landmarks shifted by -c (zero-centred).
std::vector<Landmark> shifted(const std::vector<Landmark>& lms, const Eigen::Vector3d& c) {
  std::vector<Landmark> out = lms;
  for (Landmark& l : out) l.p -= c;
  return out;
}

// Exact score of (yaw, tx, ty): B's landmarks with a same-class, size-agreeing landmark of A
// within the match radius (xy).
double exactScore(const ClassGrid& grid, const std::vector<Landmark>& b, double yaw, double tx, double ty,
                  const VerifyParams& vp) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  int n = 0;
  for (const Landmark& l : b) {
    const double x = c * l.p.x() - s * l.p.y() + tx, y = s * l.p.x() + c * l.p.y() + ty;
    if (grid.nearestWithin(l.class_id, x, y, vp.match_radius, l.size, vp.size_tolerance) >= 0) ++n;
  }
  return n;
}

// Best exact score on a (2k+1)^3 grid around `c` with the given steps.
Candidate refineAround(const ClassGrid& grid, const std::vector<Landmark>& b, const Candidate& c, double yaw_step,
                       double t_step, int k, const VerifyParams& vp) {
  Candidate best = c;
  best.score = exactScore(grid, b, c.yaw, c.tx, c.ty, vp);
  for (int i = -k; i <= k; ++i)
    for (int jx = -k; jx <= k; ++jx)
      for (int jy = -k; jy <= k; ++jy) {
        const Candidate q{0, c.yaw + i * yaw_step, c.tx + jx * t_step, c.ty + jy * t_step};
        const double s = exactScore(grid, b, q.yaw, q.tx, q.ty, vp);
        if (s > best.score) best = {s, q.yaw, q.tx, q.ty};
      }
  return best;
}
}  // namespace

PlaceResult slideMatch(const std::vector<Landmark>& a_in, const std::vector<Landmark>& b_in,
                       const SlideMatchParams& params) {
  const auto t0 = Clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); };
  const double cpu0 = threadCpuMs();
  PlaceResult res;
  auto finish = [&]() {
    res.ms = elapsed();
    res.cpu_ms = threadCpuMs() - cpu0;
    return res;
  };
  for (const auto& [lms, name] : {std::pair{&a_in, "map A"}, std::pair{&b_in, "map B"}}) {
    res.reason = unusableReason(*lms, std::max<std::size_t>(2, params.min_landmarks), name);
    if (!res.reason.empty()) return finish();
  }
  const Eigen::Vector3d ca = centroidOf(a_in), cb = centroidOf(b_in);
  const std::vector<Landmark> a = shifted(a_in, ca), b = shifted(b_in, cb);

  // Search region and yaw step, from the maps' extents.
  double ax0 = 1e300, ax1 = -1e300, ay0 = 1e300, ay1 = -1e300;
  for (const Landmark& l : a) {
    ax0 = std::min(ax0, l.p.x());
    ax1 = std::max(ax1, l.p.x());
    ay0 = std::min(ay0, l.p.y());
    ay1 = std::max(ay1, l.p.y());
  }
  std::vector<double> rb;
  for (const Landmark& l : b) rb.push_back(l.p.head<2>().norm());
  std::sort(rb.begin(), rb.end());
  const double rb_max = rb.back(), rb_90 = rb[(rb.size() * 9) / 10];
  // The coarse bin grows when the region would need more than max_coarse_bins bins (huge maps).
  const double region = (ax1 - ax0 + 2 * rb_max) * (ay1 - ay0 + 2 * rb_max);
  const double bin = std::max(params.coarse_bin, std::sqrt(region / static_cast<double>(params.max_coarse_bins)) + 1e-9);
  const double tx0 = ax0 - rb_max - bin, ty0 = ay0 - rb_max - bin;
  const long nx = static_cast<long>((ax1 - ax0 + 2 * rb_max + 2 * bin) / bin) + 1;
  const long ny = static_cast<long>((ay1 - ay0 + 2 * rb_max + 2 * bin) / bin) + 1;
  const double deg = M_PI / 180.0;
  double yaw_step = 2.0 * std::asin(std::min(1.0, 0.5 * bin / std::max(rb_90, 1e-3)));
  yaw_step = std::clamp(yaw_step, params.min_yaw_step_deg * deg, params.max_yaw_step_deg * deg);
  const int n_yaw = static_cast<int>(std::ceil(2 * M_PI / yaw_step));
  yaw_step = 2 * M_PI / n_yaw;

  // Per-class structure-of-arrays of A for the voting loop.
  std::map<int, std::pair<std::vector<float>, std::vector<float>>> a_by_class;
  for (const Landmark& l : a) {
    auto& [xs, ys] = a_by_class[l.class_id];
    xs.push_back(static_cast<float>(l.p.x()));
    ys.push_back(static_cast<float>(l.p.y()));
  }

  // Coarse stage: translation voting per yaw, yaws outward from zero.
  std::vector<std::int32_t> acc(static_cast<std::size_t>(nx * ny));
  std::vector<Candidate> peaks;  // best per yaw
  int visited = 0;
  for (int k = 0; k < n_yaw; ++k) {
    const int step = (k + 1) / 2 * (k % 2 ? 1 : -1);  // 0, +1, -1, +2, -2, ...
    const double yaw = step * yaw_step;
    const float c = static_cast<float>(std::cos(yaw)), s = static_cast<float>(std::sin(yaw));
    std::fill(acc.begin(), acc.end(), 0);
    const float inv = static_cast<float>(1.0 / bin), fx0 = static_cast<float>(tx0), fy0 = static_cast<float>(ty0);
    bool out_of_time = false;
    for (std::size_t jb = 0; jb < b.size() && !out_of_time; ++jb) {
      // Very large maps: the budget is also checked within a yaw (the first yaw always completes).
      if (k > 0 && jb % 64 == 63 && elapsed() > params.budget_ms) out_of_time = true;
      const Landmark& l = b[jb];
      const auto it = a_by_class.find(l.class_id);
      if (it == a_by_class.end()) continue;
      const float qx = c * static_cast<float>(l.p.x()) - s * static_cast<float>(l.p.y());
      const float qy = s * static_cast<float>(l.p.x()) + c * static_cast<float>(l.p.y());
      const std::vector<float>& xs = it->second.first;
      const std::vector<float>& ys = it->second.second;
      const float ox = -qx - fx0, oy = -qy - fy0;
      for (std::size_t i = 0; i < xs.size(); ++i) {
        const long ix = static_cast<long>((xs[i] + ox) * inv), iy = static_cast<long>((ys[i] + oy) * inv);
        // The region covers every pair's translation; the check guards float rounding.
        if (ix >= 0 && ix < nx && iy >= 0 && iy < ny) ++acc[iy * nx + ix];
      }
    }
    if (out_of_time) {
      res.budget_exhausted = true;
      break;
    }
    // Peak of 2x2 bin sums (a true peak straddles bin borders).
    Candidate best;
    for (long iy = 0; iy + 1 < ny; ++iy)
      for (long ix = 0; ix + 1 < nx; ++ix) {
        const long i = iy * nx + ix;
        const double v = acc[i] + acc[i + 1] + acc[i + nx] + acc[i + nx + 1];
        if (v > best.score) best = {v, yaw, tx0 + (ix + 1) * bin, ty0 + (iy + 1) * bin};
      }
    peaks.push_back(best);
    ++visited;
    if (elapsed() > params.budget_ms && k + 1 < n_yaw) {
      res.budget_exhausted = true;
      break;
    }
  }

  res.stage_cpu_ms.emplace_back("coarse_voting", threadCpuMs() - cpu0);
  // Fine stage on the strongest distinct peaks.
  std::sort(peaks.begin(), peaks.end(), [](const Candidate& x, const Candidate& y) { return x.score > y.score; });
  std::vector<Candidate> tops;
  for (const Candidate& p : peaks) {
    bool distinct = true;
    for (const Candidate& t : tops)
      distinct &= std::abs(wrapAngle(p.yaw - t.yaw)) > 1.5 * yaw_step || std::hypot(p.tx - t.tx, p.ty - t.ty) > 2 * bin;
    if (distinct) tops.push_back(p);
    if (tops.size() >= params.refine_candidates) break;
  }
  const ClassGrid grid(a, params.verify.match_radius);
  std::vector<Candidate> refined;
  for (const Candidate& t : tops) {
    Candidate c = refineAround(grid, b, t, yaw_step / 2, bin / 2, 2, params.verify);
    refined.push_back(refineAround(grid, b, c, yaw_step / 8, bin / 8, 2, params.verify));
  }
  std::stable_sort(refined.begin(), refined.end(), [](const Candidate& x, const Candidate& y) { return x.score > y.score; });
  if (refined.empty() || refined.front().score <= 0) {
    res.reason = "no class-consistent match at any searched transform";
    return finish();
  }
  // Verify every refined candidate: the strongest accepted one wins (in aliased scenes the
  // highest grid score can belong to a wrong alignment that the acceptance test rejects), and it
  // must stand against the strongest other alignment (ambiguity test).
  const LandmarkIndex index_a(a_in);
  std::vector<PlaceResult> trials;
  for (std::size_t k = 0; k < refined.size(); ++k) {
    const Candidate& best = refined[k];
    // Back to the maps' own frames; z from the matched pairs (median height offset).
    const Eigen::Matrix3d R = rotZ(best.yaw);
    std::vector<double> dz;
    for (const Landmark& l : b) {
      const Eigen::Vector3d q = R * l.p + Eigen::Vector3d(best.tx, best.ty, 0);
      const long i = grid.nearestWithin(l.class_id, q.x(), q.y(), params.verify.match_radius, l.size,
                                        params.verify.size_tolerance);
      if (i >= 0) dz.push_back(a[i].p.z() - q.z());
    }
    if (dz.empty()) continue;
    std::nth_element(dz.begin(), dz.begin() + dz.size() / 2, dz.end());
    Pose T = Pose::Identity();
    T.linear() = R;
    T.translation() = ca + Eigen::Vector3d(best.tx, best.ty, dz[dz.size() / 2]) - R * cb;
    PlaceResult trial = res;
    trial.score = best.score;
    refineAndDecide(a_in, index_a, b_in, T, params.verify, trial);
    trials.push_back(std::move(trial));
  }
  if (trials.empty()) {
    res.reason = "no candidate with a height reference";
    return finish();
  }
  std::size_t pick = 0;  // the strongest accepted trial, else the first (best grid score)
  for (std::size_t k = 0; k < trials.size(); ++k)
    if (trials[k].found && (!trials[pick].found || strengthOf(trials[k]) > strengthOf(trials[pick]))) pick = k;
  PlaceResult chosen = trials[pick];
  standsAgainstRival(rivalOf(chosen, trials, b_in, params.verify), params.verify, chosen);
  res = std::move(chosen);
  if (!res.found && res.budget_exhausted)
    res.reason += " (time budget ran out after " + std::to_string(visited) + " of " + std::to_string(n_yaw) + " yaws)";
  return finish();
}

}  // namespace slide
