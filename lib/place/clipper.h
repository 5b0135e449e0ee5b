#pragma once
// CLIPPER (Lusk, Fathian, How, ICRA 2021): the largest mutually consistent subset of putative
// associations. Relaxed densest-subgraph problem max u'Mu over the unit sphere with u >= 0,
// solved by projected gradient ascent while a growing penalty d u'Cu pushes apart
// inconsistent pairs (C = complement of the consistency graph, applied without forming it);
// then rounding to a clique, greedily in decreasing order of u. Deterministic: the start
// vector comes from a seeded generator.
#include <cstdint>
#include <vector>

#include "place/consistency_graph.h"

namespace slide::place {

struct ClipperParams {
  ConsistencyParams consistency;
  std::uint32_t seed = 7;
  int max_outer = 40;        // penalty increases
  int max_inner = 200;       // gradient steps per penalty value
  double tol_f = 1e-6;       // relative change of the objective that ends the inner loop
  double support_eps = 1e-3; // entries below this fraction of max(u) are outside the support
};

struct ClipperResult {
  std::vector<std::size_t> selected;  // indices into the associations, pairwise consistent
  std::size_t edges = 0;              // consistent pairs in the graph
  std::size_t peak_bytes = 0;         // peak bytes of the graph and the solver's vectors
  int outer_iterations = 0;
  double density = 0;                 // u'Mu at the solution
};

// Solves on a built graph; when `active` is given, only associations with active[i] != 0 take
// part (the others are treated as removed, without rebuilding the graph).
ClipperResult solveClipper(const ConsistencyGraph& graph, const ClipperParams& params,
                           const std::vector<char>* active = nullptr);

// Builds the graph of `assoc` over positions pa (map A) and pb (map B), then solves.
ClipperResult clipper(const std::vector<Eigen::Vector3d>& pa, const std::vector<Eigen::Vector3d>& pb,
                      const std::vector<Association>& assoc, const ClipperParams& params);

}  // namespace slide::place
