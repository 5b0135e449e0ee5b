#pragma once
// The sparse consistency graph of CLIPPER (Lusk et al., ICRA 2021) over putative associations
// (landmark i of A <-> landmark j of B). Two associations are consistent when they use four
// distinct landmarks and preserve distance: c = | |a_i - a_k| - |b_j - b_l| | < epsilon; the
// edge weight is exp(-c^2 / (2 sigma^2)). Only consistent pairs are stored (CSR), so memory
// grows with the number of consistent pairs, never with m x m.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace slide::place {

struct Association {
  std::uint32_t a = 0;  // landmark index in map A
  std::uint32_t b = 0;  // landmark index in map B
};

struct ConsistencyParams {
  double sigma = 0.3;    // metres
  double epsilon = 0.6;  // metres: pairs with c >= epsilon are inconsistent
};

class ConsistencyGraph {
 public:
  ConsistencyGraph() = default;
  ConsistencyGraph(const std::vector<Eigen::Vector3d>& pa, const std::vector<Eigen::Vector3d>& pb,
                   const std::vector<Association>& assoc, const ConsistencyParams& params);

  std::size_t size() const { return offsets_.empty() ? 0 : offsets_.size() - 1; }
  std::size_t numEdges() const { return neighbors_.size() / 2; }  // each edge is stored twice
  // Neighbours of association u (sorted) and their weights.
  const std::uint32_t* neighborsBegin(std::size_t u) const { return neighbors_.data() + offsets_[u]; }
  const std::uint32_t* neighborsEnd(std::size_t u) const { return neighbors_.data() + offsets_[u + 1]; }
  const float* weightsBegin(std::size_t u) const { return weights_.data() + offsets_[u]; }
  bool consistent(std::size_t u, std::size_t v) const;
  // Largest number of bytes held at once while building and storing the graph.
  std::size_t peakBytes() const { return peak_bytes_; }

 private:
  std::vector<std::size_t> offsets_;
  std::vector<std::uint32_t> neighbors_;
  std::vector<float> weights_;
  std::size_t peak_bytes_ = 0;
};

}  // namespace slide::place
