#include "place/consistency_graph.h"

#include <algorithm>
#include <cmath>

namespace slide::place {

ConsistencyGraph::ConsistencyGraph(const std::vector<Eigen::Vector3d>& pa, const std::vector<Eigen::Vector3d>& pb,
                                   const std::vector<Association>& assoc, const ConsistencyParams& params) {
  const std::size_t m = assoc.size();
  struct Edge {
    std::uint32_t u, v;
    float w;
  };
  // Pass 1: consistent pairs as a growing edge list (only what is consistent is stored).
  std::vector<Edge> edges;
  std::vector<std::size_t> degree(m, 0);
  const double inv2s2 = 1.0 / (2.0 * params.sigma * params.sigma);
  for (std::size_t u = 0; u < m; ++u) {
    const Eigen::Vector3d& ai = pa[assoc[u].a];
    const Eigen::Vector3d& bj = pb[assoc[u].b];
    for (std::size_t v = u + 1; v < m; ++v) {
      if (assoc[v].a == assoc[u].a || assoc[v].b == assoc[u].b) continue;
      const double c = std::abs((ai - pa[assoc[v].a]).norm() - (bj - pb[assoc[v].b]).norm());
      if (c >= params.epsilon) continue;
      edges.push_back({static_cast<std::uint32_t>(u), static_cast<std::uint32_t>(v),
                       static_cast<float>(std::exp(-c * c * inv2s2))});
      ++degree[u];
      ++degree[v];
    }
  }
  // Pass 2: compressed rows, both directions, neighbours sorted.
  offsets_.assign(m + 1, 0);
  for (std::size_t u = 0; u < m; ++u) offsets_[u + 1] = offsets_[u] + degree[u];
  neighbors_.resize(offsets_[m]);
  weights_.resize(offsets_[m]);
  peak_bytes_ = edges.capacity() * sizeof(Edge) + degree.capacity() * sizeof(std::size_t) +
                offsets_.capacity() * sizeof(std::size_t) + neighbors_.capacity() * sizeof(std::uint32_t) +
                weights_.capacity() * sizeof(float);
  // Edges are ordered by (u, v): filling every row first with its smaller neighbours (the
  // mirrored half) and then with its larger ones leaves each row sorted.
  std::vector<std::size_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (const Edge& e : edges) {
    neighbors_[fill[e.v]] = e.u;
    weights_[fill[e.v]++] = e.w;
  }
  for (const Edge& e : edges) {
    neighbors_[fill[e.u]] = e.v;
    weights_[fill[e.u]++] = e.w;
  }
}

bool ConsistencyGraph::consistent(std::size_t u, std::size_t v) const {
  return std::binary_search(neighborsBegin(u), neighborsEnd(u), static_cast<std::uint32_t>(v));
}

}  // namespace slide::place
