#include "place/slidegraph.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <map>

#include "place/alignment.h"
#include "place/simplex_descriptor.h"

namespace slide::place {

namespace {
std::vector<Triangle> triangulate(const std::vector<Landmark>& lms, const std::function<bool()>& out_of_time) {
  std::vector<Eigen::Vector2d> xy;
  xy.reserve(lms.size());
  for (const Landmark& l : lms) xy.push_back(l.p.head<2>());
  return delaunay2d(xy, out_of_time);
}

struct Vote {
  std::uint32_t votes = 0;
  double best = 1e300;  // smallest descriptor distance among its triangle pairs
};

// Vertex associations from descriptor matches, strongest first, at most max_associations;
// none once out_of_time says true (polled every 1024 descriptors of A).
std::vector<Association> associate(const std::vector<SimplexDescriptor>& da, const std::vector<SimplexDescriptor>& db,
                                   const SlideGraphParams& params, const std::function<bool()>& out_of_time) {
  // One k-d tree per vertex-class triple of B (a single one when classes are ignored).
  struct Group {
    std::vector<Eigen::Vector3d> keys;
    std::vector<std::size_t> members;
    KdTree<3> tree;
  };
  std::map<std::array<int, 3>, Group> groups;
  const std::array<int, 3> any{0, 0, 0};
  for (std::size_t j = 0; j < db.size(); ++j) {
    Group& g = groups[params.use_classes ? db[j].classes : any];
    g.keys.push_back(db[j].distances);
    g.members.push_back(j);
  }
  for (auto& [key, g] : groups) g.tree = KdTree<3>(g.keys);
  if (out_of_time()) return {};
  // Each vertex correspondence of each matched triangle pair, as (A vertex << 32 | B vertex,
  // descriptor distance); sorted by key, runs of one key are one association's votes. (A hash
  // map of votes cost most of this stage on 10,000-landmark maps: a cache miss per vote.)
  struct Hit {
    std::uint64_t key;
    double dist;
  };
  std::vector<Hit> hits;
  hits.reserve(da.size() * params.neighbors_per_simplex * 3);
  const double r2 = params.descriptor_radius * params.descriptor_radius;
  for (std::size_t i = 0; i < da.size(); ++i) {
    if (i % 1024 == 1023 && out_of_time()) return {};
    const SimplexDescriptor& d = da[i];
    const auto it = groups.find(params.use_classes ? d.classes : any);
    if (it == groups.end()) continue;
    for (const auto& [k, dist2] : it->second.tree.nearest(d.distances, params.neighbors_per_simplex)) {
      if (dist2 > r2) break;  // nearest first
      const SimplexDescriptor& e = db[it->second.members[k]];
      for (int v = 0; v < 3; ++v)
        hits.push_back({(static_cast<std::uint64_t>(d.vertices[v]) << 32) | e.vertices[v], std::sqrt(dist2)});
    }
  }
  std::sort(hits.begin(), hits.end(), [](const Hit& x, const Hit& y) { return x.key < y.key; });
  std::vector<std::pair<std::uint64_t, Vote>> ranked;
  for (std::size_t k = 0; k < hits.size();) {
    Vote vote;
    const std::uint64_t key = hits[k].key;
    for (; k < hits.size() && hits[k].key == key; ++k) {
      ++vote.votes;
      vote.best = std::min(vote.best, hits[k].dist);
    }
    ranked.emplace_back(key, vote);
  }
  // The strongest max_associations, in order (keys are unique: the order is total).
  const std::size_t keep = std::min(ranked.size(), params.max_associations);
  std::partial_sort(ranked.begin(), ranked.begin() + static_cast<std::ptrdiff_t>(keep), ranked.end(),
                    [](const auto& x, const auto& y) {
                      if (x.second.votes != y.second.votes) return x.second.votes > y.second.votes;
                      if (x.second.best != y.second.best) return x.second.best < y.second.best;
                      return x.first < y.first;
                    });
  ranked.resize(keep);
  const auto weak = std::find_if(ranked.begin(), ranked.end(), [&](const auto& r) { return r.second.votes < params.min_votes; });
  if (static_cast<std::size_t>(weak - ranked.begin()) >= params.min_voted) ranked.erase(weak, ranked.end());
  std::vector<Association> out;
  out.reserve(ranked.size());
  for (const auto& [key, v] : ranked)
    out.push_back({static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key & 0xffffffffu)});
  return out;
}
}  // namespace

PlaceResult slideGraph(const std::vector<Landmark>& a, const std::vector<Landmark>& b, const SlideGraphParams& params) {
  PlaceResult res = slideGraphOnce(a, b, params);
  if (res.found || a.size() > params.small_map || b.size() > params.small_map || params.retry_tolerance_scale <= 1.0 ||
      res.associations == 0 || res.budget_exhausted || res.cpu_ms >= params.budget_ms)
    return res;
  SlideGraphParams loose = params;
  loose.budget_ms = params.budget_ms - res.cpu_ms;  // the retry spends what is left
  loose.descriptor_radius *= params.retry_tolerance_scale;
  loose.clipper.consistency.sigma *= params.retry_tolerance_scale;
  loose.clipper.consistency.epsilon *= params.retry_tolerance_scale;
  PlaceResult retry = slideGraphOnce(a, b, loose);
  retry.ms += res.ms;
  retry.cpu_ms += res.cpu_ms;
  retry.stage_cpu_ms.insert(retry.stage_cpu_ms.begin(), res.stage_cpu_ms.begin(), res.stage_cpu_ms.end());
  if (retry.found || retry.budget_exhausted) return retry;
  res.ms = retry.ms;
  res.cpu_ms = retry.cpu_ms;
  res.stage_cpu_ms = retry.stage_cpu_ms;
  return res;
}

PlaceResult slideGraphOnce(const std::vector<Landmark>& a, const std::vector<Landmark>& b, const SlideGraphParams& params) {
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = clock::threadCpuMs();
  double cpu_mark = cpu0;
  PlaceResult res;
  auto stage = [&](const char* name) {
    const double now = clock::threadCpuMs();
    res.stage_cpu_ms.emplace_back(name, now - cpu_mark);
    cpu_mark = now;
  };
  auto finish = [&]() {
    res.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    res.cpu_ms = clock::threadCpuMs() - cpu0;
    return res;
  };
  // The budget is the calling thread's CPU time: other processes' load does not eat it.
  const std::function<bool()> out_of_time = [&] { return clock::threadCpuMs() - cpu0 > params.budget_ms; };
  auto budgetExceeded = [&](const char* where) {  // no result: the budget ran out first
    res.found = false;
    res.inliers.clear();
    res.budget_exhausted = true;
    char buf[96];
    std::snprintf(buf, sizeof buf, "CPU time budget of %g ms exceeded in %s", params.budget_ms, where);
    res.reason = std::string(buf) + " (no result; " + std::to_string(a.size()) + " and " + std::to_string(b.size()) +
                 " landmarks)";
    return finish();
  };
  for (const auto& [lms, name] : {std::pair{&a, "map A"}, std::pair{&b, "map B"}}) {
    res.reason = unusableReason(*lms, std::max<std::size_t>(3, params.min_landmarks), name);
    if (!res.reason.empty()) return finish();
  }
  const std::vector<Triangle> ta = triangulate(a, out_of_time);
  const std::vector<Triangle> tb = out_of_time() ? std::vector<Triangle>{} : triangulate(b, out_of_time);
  stage("triangulate");
  if (out_of_time()) return budgetExceeded("triangulation");
  if (ta.empty() || tb.empty()) {
    res.reason = std::string(ta.empty() ? "map A" : "map B") + " has no triangles (collinear or duplicate points)";
    return finish();
  }
  const std::vector<Association> assoc =
      associate(describeTriangles(a, ta), describeTriangles(b, tb), params, out_of_time);
  res.associations = assoc.size();
  stage("associate");
  if (out_of_time()) return budgetExceeded("association");
  if (assoc.size() < 3) {
    res.reason = "only " + std::to_string(assoc.size()) + " associations from simplex descriptors";
    return finish();
  }
  std::vector<Eigen::Vector3d> pa, pb;
  for (const Landmark& l : a) pa.push_back(l.p);
  for (const Landmark& l : b) pb.push_back(l.p);
  const LandmarkIndex index_a(a), index_b(b);
  // Hypotheses: CLIPPER's densest consistent set, verified; when rejected (and not already
  // smaller than an acceptable inlier set), CLIPPER again without those associations: aliased
  // scenes can hold several consistent sets.
  const ConsistencyGraph graph(pa, pb, assoc, params.clipper.consistency);
  stage("consistency_graph");
  if (out_of_time()) return budgetExceeded("the consistency graph");
  res.clipper_edges = graph.numEdges();
  std::vector<char> active(assoc.size(), 1);
  const bool small = a.size() <= params.small_map && b.size() <= params.small_map;
  PlaceResult first, best;
  std::vector<PlaceResult> tried;
  for (int h = 0; h < std::max(1, params.hypotheses); ++h) {
    if (h > 0 && out_of_time()) {  // a verified transform stands; otherwise no result
      if (best.found) break;
      return budgetExceeded("hypothesis verification");
    }
    const ClipperResult cl = solveClipper(graph, params.clipper, &active);
    stage("clipper");
    res.clipper_peak_bytes = std::max(res.clipper_peak_bytes, cl.peak_bytes);
    PlaceResult trial = res;
    trial.score = static_cast<double>(cl.selected.size());
    if (cl.selected.size() < 3) {
      trial.reason = "CLIPPER kept " + std::to_string(cl.selected.size()) + " consistent associations, fewer than 3";
      if (h == 0) first = trial;
      break;
    }
    std::vector<Eigen::Vector3d> sa, sb;
    for (std::size_t k : cl.selected) {
      sa.push_back(pa[assoc[k].a]);
      sb.push_back(pb[assoc[k].b]);
    }
    const Alignment seed = alignXyzYawRobust(sa, sb, params.verify.robust_scale);
    if (seed.ok) {
      refineAndDecide(a, index_a, b, index_b, seed.T_a_b, params.verify, trial);
    } else {
      trial.reason = "CLIPPER's consistent set is degenerate (all B points coincide)";
    }
    stage("verify");
    tried.push_back(trial);
    // Large maps: the first accepted set wins. Small maps (cheap): every hypothesis is
    // verified and the one with most inliers wins, as a small alias can pass the test too.
    // Either way it must stand against the other alignments verified (ambiguity test).
    if (trial.found && (!small || h + 1 >= std::max(1, params.hypotheses))) {
      if (best.found && best.inliers.size() >= trial.inliers.size()) break;
      res = std::move(trial);
      standsAgainstRival(rivalOf(res, tried, b, params.verify), params.verify, res);
      return finish();
    }
    if (trial.found && (!best.found || trial.inliers.size() > best.inliers.size())) best = trial;
    if (h == 0) first = trial;
    if (cl.selected.size() < params.verify.min_inliers) break;  // later sets are no denser
    for (std::size_t k : cl.selected) active[k] = 0;
  }
  if (best.found) first = best;
  first.stage_cpu_ms = res.stage_cpu_ms;
  first.clipper_edges = res.clipper_edges;
  first.clipper_peak_bytes = res.clipper_peak_bytes;
  res = std::move(first);
  if (res.found) standsAgainstRival(rivalOf(res, tried, b, params.verify), params.verify, res);
  return finish();
}

}  // namespace slide::place
