#pragma once
// The factor graph that never forgets: every variable and factor ever added stays (until a
// factor is explicitly replaced). Local solves build a small problem over chosen variables,
// with every factor touching them and the rest held constant; full solves work on a snapshot
// (a copy of the values sharing the factors' cost functions), so they can run on another
// thread while the graph grows; batch solves rebuild everything from the initial values.
// Ceres stays out of this header.
#include <array>
#include <atomic>
#include <deque>
#include <memory>
#include <string>
#include <vector>

namespace ceres {
class CostFunction;
class LossFunction;
class Manifold;
class Problem;
}  // namespace ceres

namespace slide::backend {

enum class BlockKind { Pose, Cylinder, Vector3, Scalar };  // sizes 7, 7, 3, 1

struct SolveReport {
  double initial_cost = 0;
  double final_cost = 0;
  int iterations = 0;
  int residual_blocks = 0;
  bool aborted = false;  // cancelled: the values are not a solution
  double wall_ms = 0;    // wall time of the solve (full solves: building the problem included)
  std::string message;  // the solver's termination message
};

class FactorGraph {
 public:
  using Values = std::vector<std::array<double, 7>>;

  // The graph as it was when taken: every variable's value and kind, and the factors then
  // alive, sharing their cost functions, losses and manifolds (so it outlives factors removed
  // from the graph, and the graph itself). Solving it touches nothing of the graph.
  struct Snapshot {
    struct Term {
      std::shared_ptr<ceres::CostFunction> cost;
      ceres::LossFunction* loss = nullptr;
      int factor = 0;             // id in the graph (-1: added to the snapshot only)
      int first = 0, count = 0;   // its variables: vars[first .. first + count)
    };
    std::vector<BlockKind> kinds;
    std::vector<char> eliminate_first, removed;
    Values values;
    std::vector<Term> terms;
    std::vector<int> vars;
    std::size_t num_factors = 0;  // factor ids below this existed when it was taken
    std::vector<std::shared_ptr<ceres::LossFunction>> losses;
    std::shared_ptr<ceres::Manifold> pose_manifold, cylinder_manifold;
  };
  struct FullSolveOptions {
    int max_iterations = 100;
    double function_tolerance = 1e-6;
    int num_threads = 1;
    // The graph is warm (its values are the last solution), so Levenberg-Marquardt may start
    // with a wide trust region (Ceres's default 1e4 damps the long, weakly constrained modes a
    // loop closure moves and needs several extra iterations for them).
    double trust_region_radius = 1e4;
    double max_seconds = 0;                      // > 0: stop after this long (checked per iteration)
    const std::atomic<bool>* cancel = nullptr;   // set: abort at the next iteration
  };

  // Robust losses on object factors: Huber on the whitened residual norm with threshold
  // robust_loss_scale * sqrt(number of residuals), so a block whose error matches its noise
  // model keeps its full (quadratic) weight whatever its dimension.
  explicit FactorGraph(double robust_loss_scale = 1.5);
  ~FactorGraph();
  FactorGraph(const FactorGraph&) = delete;
  FactorGraph& operator=(const FactorGraph&) = delete;
  FactorGraph(FactorGraph&&) noexcept;
  FactorGraph& operator=(FactorGraph&&) noexcept;

  // Schur solves eliminate group 0 (landmark blocks, which never share a factor) first, then
  // the rest (key poses, and landmark blocks that accompany a group-0 block such as cuboid
  // dims). `init` has the block's size.
  int addVariable(BlockKind kind, const double* init, bool eliminate_first);
  // Takes ownership of `cost`; its parameter blocks are `vars` in order.
  int addFactor(ceres::CostFunction* cost, std::vector<int> vars, bool robust);
  void removeFactor(int factor);
  // Drops a variable no factor uses any more (e.g. a landmark merged into another).
  void removeVariable(int var);

  double* value(int var) { return vars_[var].value.data(); }
  const double* value(int var) const { return vars_[var].value.data(); }
  const std::vector<int>& factorsOf(int var) const { return vars_[var].factors; }
  std::size_t numVariables() const { return vars_.size(); }
  std::size_t numFactors() const { return factors_.size() - removed_; }
  bool eliminatedFirst(int var) const { return vars_[var].eliminate_first; }

  // Solves over `active` variables with every factor that touches one of them; stops once an
  // iteration lowers the cost by less than function_tolerance (relative).
  SolveReport solveLocal(const std::vector<int>& active, int max_iterations, double function_tolerance = 1e-6);
  // Solves over every variable: solveSnapshot on a snapshot whose values are then taken back.
  SolveReport solveFull(int max_iterations, double function_tolerance, int num_threads = 1,
                        double trust_region_radius = 1e4);
  Snapshot snapshot() const;
  // Adds a factor to a snapshot only (not to any graph; its id is -1): e.g. a loop closure that
  // enters the graph once the snapshot's solution is taken in. Takes ownership of `cost`.
  static void addToSnapshot(Snapshot& s, ceres::CostFunction* cost, const std::vector<int>& vars);
  // Solves every variable of `s` in place; safe on any thread. With `residual_norms`, fills
  // the whitened residual norm of each factor at the solution, by factor id (0 for factors
  // not in the snapshot). A cancelled solve reports aborted and leaves no norms.
  static SolveReport solveSnapshot(Snapshot& s, const FullSolveOptions& o, std::vector<double>* residual_norms = nullptr);
  // Sets a variable's value (e.g. from a solved snapshot); `v` has the block's size.
  void setValue(int var, const double* v);
  bool removedVariable(int var) const { return vars_[var].removed; }
  std::size_t numFactorIds() const { return factors_.size(); }  // ids ever given, removed ones too
  // Solves a fresh problem of the same factors starting from each variable's initial value;
  // returns the solution without touching the graph's values.
  Values solveBatch(int max_iterations, double function_tolerance, SolveReport* report = nullptr,
                    int num_threads = 1) const;
  Values values() const;
  // Norm of a factor's (whitened) residual at the current values, and its dimension.
  double residualNorm(int factor) const;
  int residualCount(int factor) const;
  double cost() const;  // total cost (robust losses applied) at the current values

 private:
  struct Variable {
    BlockKind kind;
    bool eliminate_first;
    std::array<double, 7> value;
    std::array<double, 7> initial;
    std::vector<int> factors;
    bool removed = false;
  };
  struct Factor {
    std::shared_ptr<ceres::CostFunction> cost;  // shared with snapshots being solved
    std::vector<int> vars;
    bool robust = false;
    bool removed = false;
  };
  ceres::Manifold* manifoldFor(BlockKind kind) const;
  ceres::LossFunction* lossFor(const Factor& f) const;
  void addToProblem(ceres::Problem& p, const Factor& f, std::vector<double*>& blocks, Values* storage) const;

  std::deque<Variable> vars_;  // deque: block addresses stay valid as variables are added
  std::vector<Factor> factors_;
  std::size_t removed_ = 0;
  double robust_scale_;
  std::vector<std::shared_ptr<ceres::LossFunction>> losses_;  // by residual count
  std::shared_ptr<ceres::Manifold> pose_manifold_, cylinder_manifold_;
};

}  // namespace slide::backend
