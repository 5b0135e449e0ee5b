#include "place/slidegraph.h"

#include <algorithm>
#include <chrono>
#include <unordered_map>

#include "place/alignment.h"
#include "place/simplex_descriptor.h"

namespace slide {

namespace {
std::vector<Triangle> triangulate(const std::vector<Landmark>& lms) {
  std::vector<Eigen::Vector2d> xy;
  xy.reserve(lms.size());
  for (const Landmark& l : lms) xy.push_back(l.p.head<2>());
  return delaunay2d(xy);
}

struct Vote {
  std::uint32_t votes = 0;
  double best = 1e300;  // smallest descriptor distance among its triangle pairs
};

// Vertex associations from descriptor matches, strongest first, at most max_associations.
std::vector<Association> associate(const std::vector<SimplexDescriptor>& da, const std::vector<SimplexDescriptor>& db,
                                   const SlideGraphParams& params) {
  std::vector<Eigen::Vector3d> keys;
  keys.reserve(db.size());
  for (const SimplexDescriptor& d : db) keys.push_back(d.distances);
  const KdTree<3> tree(std::move(keys));
  std::unordered_map<std::uint64_t, Vote> votes;
  std::vector<std::pair<double, std::size_t>> hits;
  for (const SimplexDescriptor& d : da) {
    hits.clear();
    for (std::size_t j : tree.radius(d.distances, params.descriptor_radius)) {
      if (params.use_classes && db[j].classes != d.classes) continue;
      hits.emplace_back((db[j].distances - d.distances).norm(), j);
    }
    if (hits.size() > params.neighbors_per_simplex) {
      std::partial_sort(hits.begin(), hits.begin() + params.neighbors_per_simplex, hits.end());
      hits.resize(params.neighbors_per_simplex);
    }
    for (const auto& [dist, j] : hits)
      for (int k = 0; k < 3; ++k) {
        Vote& v = votes[(static_cast<std::uint64_t>(d.vertices[k]) << 32) | db[j].vertices[k]];
        ++v.votes;
        v.best = std::min(v.best, dist);
      }
  }
  std::vector<std::pair<std::uint64_t, Vote>> ranked(votes.begin(), votes.end());
  std::sort(ranked.begin(), ranked.end(), [](const auto& x, const auto& y) {
    if (x.second.votes != y.second.votes) return x.second.votes > y.second.votes;
    if (x.second.best != y.second.best) return x.second.best < y.second.best;
    return x.first < y.first;
  });
  if (ranked.size() > params.max_associations) ranked.resize(params.max_associations);
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
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = threadCpuMs();
  double cpu_mark = cpu0;
  PlaceResult res;
  auto stage = [&](const char* name) {
    const double now = threadCpuMs();
    res.stage_cpu_ms.emplace_back(name, now - cpu_mark);
    cpu_mark = now;
  };
  auto finish = [&]() {
    res.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    res.cpu_ms = threadCpuMs() - cpu0;
    return res;
  };
  for (const auto& [lms, name] : {std::pair{&a, "map A"}, std::pair{&b, "map B"}}) {
    res.reason = unusableReason(*lms, std::max<std::size_t>(3, params.min_landmarks), name);
    if (!res.reason.empty()) return finish();
  }
  const std::vector<Triangle> ta = triangulate(a), tb = triangulate(b);
  stage("triangulate");
  if (ta.empty() || tb.empty()) {
    res.reason = std::string(ta.empty() ? "map A" : "map B") + " has no triangles (collinear or duplicate points)";
    return finish();
  }
  const std::vector<Association> assoc = associate(describeTriangles(a, ta), describeTriangles(b, tb), params);
  res.associations = assoc.size();
  stage("associate");
  if (assoc.size() < 3) {
    res.reason = "only " + std::to_string(assoc.size()) + " associations from simplex descriptors";
    return finish();
  }
  std::vector<Eigen::Vector3d> pa, pb;
  for (const Landmark& l : a) pa.push_back(l.p);
  for (const Landmark& l : b) pb.push_back(l.p);
  const LandmarkIndex index_a(a);
  // Hypotheses: CLIPPER's densest consistent set, verified; when rejected, CLIPPER again
  // without those associations (aliased scenes can hold several consistent sets).
  std::vector<Association> remaining = assoc;
  PlaceResult first;
  for (int h = 0; h < std::max(1, params.hypotheses) && remaining.size() >= 3; ++h) {
    const ConsistencyGraph graph(pa, pb, remaining, params.clipper.consistency);
    stage("consistency_graph");
    const ClipperResult cl = solveClipper(graph, params.clipper);
    stage("clipper");
    PlaceResult trial = res;
    trial.clipper_edges = std::max(res.clipper_edges, cl.edges);
    trial.clipper_peak_bytes = std::max(res.clipper_peak_bytes, cl.peak_bytes);
    trial.score = static_cast<double>(cl.selected.size());
    res.clipper_edges = trial.clipper_edges;
    res.clipper_peak_bytes = trial.clipper_peak_bytes;
    if (cl.selected.size() < 3) {
      trial.reason = "CLIPPER kept " + std::to_string(cl.selected.size()) + " consistent associations, fewer than 3";
      if (h == 0) first = trial;
      break;
    }
    std::vector<Eigen::Vector3d> sa, sb;
    for (std::size_t k : cl.selected) {
      sa.push_back(pa[remaining[k].a]);
      sb.push_back(pb[remaining[k].b]);
    }
    const Alignment seed = alignXyzYawRobust(sa, sb, params.verify.robust_scale);
    if (seed.ok) {
      refineAndDecide(a, index_a, b, seed.T_a_b, params.verify, trial);
    } else {
      trial.reason = "CLIPPER's consistent set is degenerate (all B points coincide)";
    }
    stage("verify");
    if (trial.found) {
      res = std::move(trial);
      return finish();
    }
    if (h == 0) first = trial;
    std::vector<char> drop(remaining.size(), 0);
    for (std::size_t k : cl.selected) drop[k] = 1;
    std::vector<Association> next;
    for (std::size_t k = 0; k < remaining.size(); ++k)
      if (!drop[k]) next.push_back(remaining[k]);
    remaining.swap(next);
  }
  first.stage_cpu_ms = res.stage_cpu_ms;
  first.clipper_edges = res.clipper_edges;
  first.clipper_peak_bytes = res.clipper_peak_bytes;
  res = std::move(first);
  return finish();
}

}  // namespace slide
