#include "place/slidematch.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <unordered_map>

#include "geometry/kdtree.h"
#include "place/class_grid.h"
#include "place/neighbourhood.h"

namespace slide::place {

namespace {
using Clock = std::chrono::steady_clock;

struct Candidate {
  double score = -1;
  double yaw = 0, tx = 0, ty = 0;
  // Pruned search: the centre of B's tile whose votes made it (the fine stage rescores near it).
  bool local = false;
  double cx = 0, cy = 0;
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

// The strongest distinct candidates (best first): apart by more than 1.5 yaw steps or 2 bins.
std::vector<Candidate> distinctTops(std::vector<Candidate> peaks, double yaw_step, double bin, std::size_t n) {
  std::sort(peaks.begin(), peaks.end(), [](const Candidate& x, const Candidate& y) { return x.score > y.score; });
  std::vector<Candidate> tops;
  for (const Candidate& p : peaks) {
    bool distinct = true;
    for (const Candidate& t : tops)
      distinct &= std::abs(wrapAngle(p.yaw - t.yaw)) > 1.5 * yaw_step || std::hypot(p.tx - t.tx, p.ty - t.ty) > 2 * bin;
    if (distinct) tops.push_back(p);
    if (tops.size() >= n) break;
  }
  return tops;
}

// Pruned coarse stage (see the header): peaks of the tile votes of neighbourhood-agreeing pairs,
// as transforms of the zero-centred maps. Sets `exhausted` when the budget stopped it.
std::vector<Candidate> prunedPeaks(const std::vector<Landmark>& a, const std::vector<Landmark>& b,
                                   const SlideMatchParams& params, const std::function<bool()>& out_of_time,
                                   bool& exhausted, std::size_t& visited) {
  const Neighbourhoods na(a, params.neighbourhood_radius), nb(b, params.neighbourhood_radius);
  struct ClassTree {
    std::vector<NeighbourhoodDescriptor> keys;
    std::vector<std::size_t> members;
    KdTree<kNeighbourhoodDims> tree;
  };
  std::map<int, ClassTree> trees;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ClassTree& t = trees[a[i].class_id];
    t.keys.push_back(na.descriptor(i));
    t.members.push_back(i);
  }
  for (auto& [cls, t] : trees) t.tree = KdTree<kNeighbourhoodDims>(t.keys);
  const double deg = M_PI / 180.0, yaw_bin = std::max(params.local_yaw_bin_deg, 0.1) * deg;
  const double tile = std::max(params.tile, 1.0), vbin = std::max(params.vote_bin, 0.05);
  const long yaw_bins = std::lround(2 * M_PI / yaw_bin);
  // Vote cells: (tile x, tile y, yaw bin, landing x, landing y) packed into 64 bits; cells out of
  // the packable range (maps tens of kilometres across) are not voted for.
  struct Acc {
    double w = 0, s = 0, c = 0, x = 0, y = 0;  // weight, yaw sin / cos sums, landing sums
  };
  std::unordered_map<std::uint64_t, Acc> votes;
  auto pack = [&](long tx, long ty, long yb, long px, long py, std::uint64_t& key) {
    tx += 512, ty += 512, px += 32768, py += 32768;
    if (tx < 0 || tx >= 1024 || ty < 0 || ty >= 1024 || px < 0 || px >= 65536 || py < 0 || py >= 65536) return false;
    key = (static_cast<std::uint64_t>(tx) << 54) | (static_cast<std::uint64_t>(ty) << 44) |
          (static_cast<std::uint64_t>(yb) << 32) | (static_cast<std::uint64_t>(px) << 16) | static_cast<std::uint64_t>(py);
    return true;
  };
  std::vector<std::size_t> order(b.size());
  for (std::size_t j = 0; j < b.size(); ++j) order[j] = j;
  std::shuffle(order.begin(), order.end(), std::mt19937(12345));
  for (std::size_t n = 0; n < order.size(); ++n) {
    if (n % 64 == 63 && out_of_time()) {
      exhausted = true;
      break;
    }
    ++visited;
    const std::size_t j = order[n];
    const auto it = trees.find(b[j].class_id);
    if (it == trees.end() || nb.end(j) - nb.begin(j) < params.min_local_votes) continue;
    const long tx = static_cast<long>(std::floor(b[j].p.x() / tile)), ty = static_cast<long>(std::floor(b[j].p.y() / tile));
    const Eigen::Vector2d centre((tx + 0.5) * tile, (ty + 0.5) * tile);
    const Eigen::Vector2d arm = centre - b[j].p.head<2>();
    for (const auto& [k, d2] : it->second.tree.nearest(nb.descriptor(j), params.pruned_candidates)) {
      const std::size_t i = it->second.members[k];
      const LocalYaw ly = localYaw(na, i, nb, j, params.verify.match_radius, 1.5, yaw_bin);
      // The yaw window must hold clearly more than chance would put there (random pairs of
      // neighbours spread their votes over the circle).
      const double chance = ly.pairs * ly.window_share;
      if (ly.votes < params.min_local_votes || ly.votes < chance + params.local_significance * std::sqrt(chance)) continue;
      const Eigen::Vector2d land = a[i].p.head<2>() + Eigen::Rotation2Dd(ly.yaw) * arm;
      const long yb = std::min(yaw_bins - 1, static_cast<long>((ly.yaw + M_PI) / yaw_bin));
      std::uint64_t key;
      if (!pack(tx, ty, yb, static_cast<long>(std::floor(land.x() / vbin)), static_cast<long>(std::floor(land.y() / vbin)), key))
        continue;
      Acc& acc = votes[key];
      const double w = ly.votes - chance;
      acc.w += w, acc.s += w * std::sin(ly.yaw), acc.c += w * std::cos(ly.yaw), acc.x += w * land.x(), acc.y += w * land.y();
    }
  }
  // Each cell scored with its neighbours (yaw +-1 bin, landing +-1 bin: a true peak straddles
  // bin borders); the transform from the weighted means of that neighbourhood.
  std::vector<std::uint64_t> keys;  // in key order: ties between peaks fall the same way on every platform
  keys.reserve(votes.size());
  for (const auto& entry : votes) keys.push_back(entry.first);
  std::sort(keys.begin(), keys.end());
  std::vector<Candidate> peaks;
  for (const std::uint64_t key : keys) {
    const long tx = static_cast<long>(key >> 54) - 512, ty = static_cast<long>((key >> 44) & 1023) - 512;
    const long yb = static_cast<long>((key >> 32) & 4095), px = static_cast<long>((key >> 16) & 65535) - 32768,
               py = static_cast<long>(key & 65535) - 32768;
    Acc sum;
    for (long dy = -1; dy <= 1; ++dy)
      for (long dx = -1; dx <= 1; ++dx)
        for (long dyaw = -1; dyaw <= 1; ++dyaw) {
          std::uint64_t k;
          if (!pack(tx, ty, (yb + dyaw + yaw_bins) % yaw_bins, px + dx, py + dy, k)) continue;
          const auto f = votes.find(k);
          if (f == votes.end()) continue;
          sum.w += f->second.w, sum.s += f->second.s, sum.c += f->second.c, sum.x += f->second.x, sum.y += f->second.y;
        }
    const double yaw = std::atan2(sum.s, sum.c);
    const Eigen::Vector2d centre((tx + 0.5) * tile, (ty + 0.5) * tile);
    const Eigen::Vector2d t = Eigen::Vector2d(sum.x, sum.y) / sum.w - Eigen::Rotation2Dd(yaw) * centre;
    Candidate c{sum.w, yaw, t.x(), t.y(), true, centre.x(), centre.y()};
    peaks.push_back(c);
  }
  return distinctTops(std::move(peaks), yaw_bin, vbin, params.refine_candidates);
}
}  // namespace

PlaceResult slideMatch(const std::vector<Landmark>& a_in, const std::vector<Landmark>& b_in,
                       const SlideMatchParams& params, std::vector<PlaceResult>* trials_out) {
  const auto t0 = Clock::now();
  const double cpu0 = clock::threadCpuMs();
  if (trials_out) trials_out->clear();
  PlaceResult res;
  double cpu_mark = cpu0;
  auto stage = [&](const char* name) {
    const double now = clock::threadCpuMs();
    res.stage_cpu_ms.emplace_back(name, now - cpu_mark);
    cpu_mark = now;
  };
  auto finish = [&]() {
    res.ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    res.cpu_ms = clock::threadCpuMs() - cpu0;
    return res;
  };
  // The budget is the calling thread's CPU time: other processes' load does not eat it.
  const std::function<bool()> out_of_time = [&] { return clock::threadCpuMs() - cpu0 > params.budget_ms; };
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
  double pairs = 0;  // same-class pairs: the exhaustive vote casts this many per yaw
  for (const Landmark& l : b)
    if (const auto it = a_by_class.find(l.class_id); it != a_by_class.end()) pairs += static_cast<double>(it->second.first.size());

  std::vector<Candidate> tops;
  std::size_t visited = 0, to_visit = 0;
  const char* unit = "yaws";
  double fine_yaw = yaw_step, fine_bin = bin;
  if (pairs * n_yaw > params.exhaustive_max_votes) {
    unit = "landmarks of B";
    to_visit = b.size();
    bool exhausted = false;
    tops = prunedPeaks(a, b, params, out_of_time, exhausted, visited);
    res.budget_exhausted = exhausted;
    fine_yaw = std::max(params.local_yaw_bin_deg, 0.1) * deg;
    fine_bin = std::max(params.vote_bin, 0.05);
    stage("pruned_voting");
  } else {
    to_visit = static_cast<std::size_t>(n_yaw);
    // Coarse stage: translation voting per yaw, yaws outward from zero.
    const double tx0 = ax0 - rb_max - bin, ty0 = ay0 - rb_max - bin;
    const long nx = static_cast<long>((ax1 - ax0 + 2 * rb_max + 2 * bin) / bin) + 1;
    const long ny = static_cast<long>((ay1 - ay0 + 2 * rb_max + 2 * bin) / bin) + 1;
    std::vector<std::int32_t> acc(static_cast<std::size_t>(nx * ny));
    std::vector<Candidate> peaks;  // best per yaw
    for (int k = 0; k < n_yaw; ++k) {
      const int step = (k + 1) / 2 * (k % 2 ? 1 : -1);  // 0, +1, -1, +2, -2, ...
      const double yaw = step * yaw_step;
      const float c = static_cast<float>(std::cos(yaw)), s = static_cast<float>(std::sin(yaw));
      std::fill(acc.begin(), acc.end(), 0);
      const float inv = static_cast<float>(1.0 / bin), fx0 = static_cast<float>(tx0), fy0 = static_cast<float>(ty0);
      bool out = false;
      for (std::size_t jb = 0; jb < b.size() && !out; ++jb) {
        // Very large maps: the budget is also checked within a yaw (the first yaw always completes).
        if (k > 0 && jb % 64 == 63 && out_of_time()) out = true;
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
      if (out) {
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
      if (k + 1 < n_yaw && out_of_time()) {
        res.budget_exhausted = true;
        break;
      }
    }
    stage("coarse_voting");
    // Fine stage on the strongest distinct peaks.
    tops = distinctTops(std::move(peaks), yaw_step, bin, params.refine_candidates);
    // The tile votes too: where B overlaps A over a small part of its route, the exhaustive
    // peaks are laid where most of B lies over A (its chance votes), not where it matches.
    if (params.tile_votes && !res.budget_exhausted) {
      bool exhausted = false;
      std::size_t landmarks_visited = 0;
      for (const Candidate& c : prunedPeaks(a, b, params, out_of_time, exhausted, landmarks_visited)) tops.push_back(c);
      res.budget_exhausted = exhausted;
      stage("pruned_voting");
    }
  }
  const ClassGrid grid(a, params.verify.match_radius);
  std::vector<Candidate> refined;
  std::vector<Landmark> near;
  for (const Candidate& t : tops) {
    // A pruned peak is rescored over B's landmarks near its tile (the rest of a large bent map
    // would only add chance).
    const std::vector<Landmark>* scored = &b;
    if (t.local) {
      near.clear();
      for (const Landmark& l : b)
        if (std::hypot(l.p.x() - t.cx, l.p.y() - t.cy) <= params.tile) near.push_back(l);
      scored = &near;
    }
    const double fy = t.local ? std::max(params.local_yaw_bin_deg, 0.1) * deg : fine_yaw;
    const double fb = t.local ? std::max(params.vote_bin, 0.05) : fine_bin;
    Candidate c = refineAround(grid, *scored, t, fy / 2, fb / 2, 2, params.verify);
    c = refineAround(grid, *scored, c, fy / 8, fb / 8, 2, params.verify);
    if (t.local) c.score = exactScore(grid, b, c.yaw, c.tx, c.ty, params.verify);
    refined.push_back(c);
  }
  stage("rescore");
  std::stable_sort(refined.begin(), refined.end(), [](const Candidate& x, const Candidate& y) { return x.score > y.score; });
  if (refined.empty() || refined.front().score <= 0) {
    res.reason = "no class-consistent match at any searched transform";
    if (res.budget_exhausted)
      res.reason += " (time budget ran out after " + std::to_string(visited) + " of " + std::to_string(to_visit) + " " + unit + ")";
    return finish();
  }
  // Verify every refined candidate: the strongest accepted one wins (in aliased scenes the
  // highest grid score can belong to a wrong alignment that the acceptance test rejects), and it
  // must stand against the strongest other alignment (ambiguity test).
  const LandmarkIndex index_a(a_in), index_b(b_in);
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
    refineAndDecide(a_in, index_a, b_in, index_b, T, params.verify, trial);
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
  if (trials_out) *trials_out = std::move(trials);
  stage("verify");
  if (!res.found && res.budget_exhausted)
    res.reason += " (time budget ran out after " + std::to_string(visited) + " of " + std::to_string(to_visit) + " " + unit + ")";
  return finish();
}

}  // namespace slide::place
