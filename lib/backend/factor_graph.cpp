#include "backend/factor_graph.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <cmath>
#include <stdexcept>

#include "backend/factors.h"

namespace slide::backend {

namespace {
int blockSize(BlockKind k) { return k == BlockKind::Vector3 ? 3 : k == BlockKind::Scalar ? 1 : 7; }

ceres::Problem::Options sharedOptions() {
  ceres::Problem::Options o;
  o.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  o.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  o.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  return o;
}

SolveReport report(const ceres::Solver::Summary& s) {
  SolveReport r;
  r.aborted = s.termination_type == ceres::USER_FAILURE;
  r.initial_cost = s.initial_cost;
  r.final_cost = s.final_cost;
  r.iterations = static_cast<int>(s.iterations.size());
  r.residual_blocks = s.num_residual_blocks;
  r.message = s.message;
  return r;
}

// Stops a solve whose cancel flag is set (at the end of an iteration).
class CancelCallback : public ceres::IterationCallback {
 public:
  explicit CancelCallback(const std::atomic<bool>* cancel) : cancel_(cancel) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    return cancel_ && cancel_->load() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  const std::atomic<bool>* cancel_;
};

ceres::Manifold* manifoldOf(BlockKind kind, const FactorGraph::Snapshot& s) {
  switch (kind) {
    case BlockKind::Pose: return s.pose_manifold.get();
    case BlockKind::Cylinder: return s.cylinder_manifold.get();
    case BlockKind::Vector3:
    case BlockKind::Scalar: return nullptr;
  }
  return nullptr;
}

ceres::Solver::Options fullOptions(int max_iterations, double function_tolerance, int num_threads,
                                   double trust_region_radius = 1e4) {
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::SPARSE_SCHUR;
  o.max_num_iterations = max_iterations;
  o.function_tolerance = function_tolerance;
  o.gradient_tolerance = 1e-10;
  o.parameter_tolerance = 1e-10;
  o.num_threads = num_threads;
  o.initial_trust_region_radius = trust_region_radius;
  o.logging_type = ceres::SILENT;
  return o;
}
}  // namespace

FactorGraph::FactorGraph(double robust_loss_scale)
    : robust_scale_(robust_loss_scale),
      pose_manifold_(newPoseManifold()),
      cylinder_manifold_(newCylinderManifold()) {}

FactorGraph::~FactorGraph() = default;
FactorGraph::FactorGraph(FactorGraph&&) noexcept = default;
FactorGraph& FactorGraph::operator=(FactorGraph&&) noexcept = default;

ceres::Manifold* FactorGraph::manifoldFor(BlockKind kind) const {
  switch (kind) {
    case BlockKind::Pose: return pose_manifold_.get();
    case BlockKind::Cylinder: return cylinder_manifold_.get();
    case BlockKind::Vector3:
    case BlockKind::Scalar: return nullptr;
  }
  return nullptr;
}

ceres::LossFunction* FactorGraph::lossFor(const Factor& f) const {
  if (!f.robust) return nullptr;
  const int n = f.cost->num_residuals();
  return losses_.at(n).get();
}

int FactorGraph::addVariable(BlockKind kind, const double* init, bool eliminate_first) {
  Variable v{kind, eliminate_first, {}, {}, {}};
  v.value.fill(0);
  std::copy(init, init + blockSize(kind), v.value.begin());
  v.initial = v.value;
  vars_.push_back(v);
  return static_cast<int>(vars_.size()) - 1;
}

void FactorGraph::addToProblem(ceres::Problem& p, const Factor& f, std::vector<double*>& blocks, Values* storage) const {
  blocks.clear();
  for (int v : f.vars) {
    double* b = storage ? (*storage)[v].data() : const_cast<double*>(vars_[v].value.data());
    if (!p.HasParameterBlock(b)) p.AddParameterBlock(b, blockSize(vars_[v].kind), manifoldFor(vars_[v].kind));
    blocks.push_back(b);
  }
  p.AddResidualBlock(f.cost.get(), lossFor(f), blocks);
}

int FactorGraph::addFactor(ceres::CostFunction* cost, std::vector<int> vars, bool robust) {
  Factor f;
  f.cost.reset(cost);
  f.vars = std::move(vars);
  f.robust = robust;
  const int n = f.cost->num_residuals();
  if (static_cast<int>(losses_.size()) <= n) losses_.resize(n + 1);
  if (!losses_[n]) {
    const double a = robust_scale_ * std::sqrt(static_cast<double>(n));
    losses_[n] = std::make_shared<ceres::HuberLoss>(a);
  }
  const int id = static_cast<int>(factors_.size());
  for (int v : f.vars) vars_[v].factors.push_back(id);
  factors_.push_back(std::move(f));
  return id;
}

void FactorGraph::removeFactor(int id) {
  Factor& f = factors_[id];
  if (f.removed) return;
  for (int v : f.vars) {
    auto& list = vars_[v].factors;
    list.erase(std::remove(list.begin(), list.end(), id), list.end());
  }
  f.removed = true;
  f.cost.reset();
  ++removed_;
}

void FactorGraph::removeVariable(int var) {
  Variable& v = vars_[var];
  if (v.removed) return;
  if (!v.factors.empty()) throw std::logic_error("FactorGraph::removeVariable: variable still has factors");
  v.removed = true;
}

SolveReport FactorGraph::solveLocal(const std::vector<int>& active, int max_iterations, double function_tolerance) {
  ceres::Problem::Options po = sharedOptions();
  po.disable_all_safety_checks = true;
  ceres::Problem problem(po);
  std::vector<int> factor_ids;
  for (int v : active) factor_ids.insert(factor_ids.end(), vars_[v].factors.begin(), vars_[v].factors.end());
  std::sort(factor_ids.begin(), factor_ids.end());
  factor_ids.erase(std::unique(factor_ids.begin(), factor_ids.end()), factor_ids.end());
  std::vector<double*> blocks;
  for (int id : factor_ids) addToProblem(problem, factors_[id], blocks, nullptr);
  std::vector<char> is_active(vars_.size(), 0);
  for (int v : active) is_active[v] = 1;
  auto* ordering = new ceres::ParameterBlockOrdering;
  for (int id : factor_ids)
    for (int v : factors_[id].vars) {
      double* b = vars_[v].value.data();
      if (!is_active[v]) problem.SetParameterBlockConstant(b);
      ordering->AddElementToGroup(b, vars_[v].eliminate_first ? 0 : 1);
    }
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::DENSE_SCHUR;
  o.linear_solver_ordering.reset(ordering);
  o.max_num_iterations = max_iterations;
  o.function_tolerance = function_tolerance;
  o.logging_type = ceres::SILENT;
  o.num_threads = 1;
  ceres::Solver::Summary s;
  ceres::Solve(o, &problem, &s);
  return report(s);
}

SolveReport FactorGraph::solveFull(int max_iterations, double function_tolerance, int num_threads,
                                   double trust_region_radius) {
  Snapshot s = snapshot();
  const SolveReport r = solveSnapshot(s, {max_iterations, function_tolerance, num_threads, trust_region_radius});
  for (std::size_t i = 0; i < vars_.size(); ++i)
    if (!vars_[i].removed) vars_[i].value = s.values[i];
  return r;
}

FactorGraph::Snapshot FactorGraph::snapshot() const {
  Snapshot s;
  const std::size_t n = vars_.size();
  s.kinds.resize(n);
  s.eliminate_first.resize(n);
  s.removed.resize(n);
  s.values.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.kinds[i] = vars_[i].kind;
    s.eliminate_first[i] = vars_[i].eliminate_first;
    s.removed[i] = vars_[i].removed;
    s.values[i] = vars_[i].value;
  }
  s.terms.reserve(factors_.size() - removed_);
  s.vars.reserve(3 * (factors_.size() - removed_));
  for (std::size_t id = 0; id < factors_.size(); ++id) {
    const Factor& f = factors_[id];
    if (f.removed) continue;
    s.terms.push_back({f.cost, lossFor(f), static_cast<int>(id), static_cast<int>(s.vars.size()),
                       static_cast<int>(f.vars.size())});
    s.vars.insert(s.vars.end(), f.vars.begin(), f.vars.end());
  }
  s.num_factors = factors_.size();
  s.losses = losses_;
  s.pose_manifold = pose_manifold_;
  s.cylinder_manifold = cylinder_manifold_;
  return s;
}

void FactorGraph::addToSnapshot(Snapshot& s, ceres::CostFunction* cost, const std::vector<int>& vars) {
  s.terms.push_back({std::shared_ptr<ceres::CostFunction>(cost), nullptr, -1, static_cast<int>(s.vars.size()),
                     static_cast<int>(vars.size())});
  s.vars.insert(s.vars.end(), vars.begin(), vars.end());
}

SolveReport FactorGraph::solveSnapshot(Snapshot& s, const FullSolveOptions& opt, std::vector<double>* residual_norms) {
  const auto t0 = std::chrono::steady_clock::now();
  SolveReport aborted;
  aborted.aborted = true;
  aborted.message = "cancelled";
  if (opt.cancel && opt.cancel->load()) return aborted;
  ceres::Problem::Options po = sharedOptions();
  po.disable_all_safety_checks = true;
  ceres::Problem problem(po);
  std::vector<double*> blocks;
  for (const Snapshot::Term& t : s.terms) {
    blocks.clear();
    for (int k = 0; k < t.count; ++k) {
      const int v = s.vars[t.first + k];
      double* b = s.values[v].data();
      if (!problem.HasParameterBlock(b)) problem.AddParameterBlock(b, blockSize(s.kinds[v]), manifoldOf(s.kinds[v], s));
      blocks.push_back(b);
    }
    problem.AddResidualBlock(t.cost.get(), t.loss, blocks);
  }
  if (opt.cancel && opt.cancel->load()) return aborted;
  ceres::Solver::Options o = fullOptions(opt.max_iterations, opt.function_tolerance, opt.num_threads,
                                         opt.trust_region_radius);
  if (opt.max_seconds > 0) o.max_solver_time_in_seconds = opt.max_seconds;
  auto* ordering = new ceres::ParameterBlockOrdering;
  for (std::size_t i = 0; i < s.values.size(); ++i)
    if (!s.removed[i] && problem.HasParameterBlock(s.values[i].data()))
      ordering->AddElementToGroup(s.values[i].data(), s.eliminate_first[i] ? 0 : 1);
  o.linear_solver_ordering.reset(ordering);
  CancelCallback callback(opt.cancel);
  if (opt.cancel) o.callbacks.push_back(&callback);
  ceres::Solver::Summary summary;
  ceres::Solve(o, &problem, &summary);
  SolveReport r = report(summary);
  r.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (r.aborted || !residual_norms) return r;
  residual_norms->assign(s.num_factors, 0.0);
  std::vector<const double*> params;
  std::vector<double> res;
  for (const Snapshot::Term& t : s.terms) {
    if (t.factor < 0) continue;
    params.clear();
    for (int k = 0; k < t.count; ++k) params.push_back(s.values[s.vars[t.first + k]].data());
    res.resize(t.cost->num_residuals());
    double sq = 0;
    if (!t.cost->Evaluate(params.data(), res.data(), nullptr)) sq = std::numeric_limits<double>::infinity();
    for (double x : res) sq += x * x;
    (*residual_norms)[t.factor] = std::sqrt(sq);
  }
  return r;
}

void FactorGraph::setValue(int var, const double* v) {
  std::copy(v, v + blockSize(vars_[var].kind), vars_[var].value.begin());
}

FactorGraph::Values FactorGraph::solveBatch(int max_iterations, double function_tolerance, SolveReport* out,
                                            int num_threads) const {
  Values values(vars_.size());
  for (std::size_t i = 0; i < vars_.size(); ++i) values[i] = vars_[i].initial;
  ceres::Problem problem(sharedOptions());
  std::vector<double*> blocks;
  for (const Factor& f : factors_)
    if (!f.removed) addToProblem(problem, f, blocks, &values);
  ceres::Solver::Options o = fullOptions(max_iterations, function_tolerance, num_threads);
  auto* ordering = new ceres::ParameterBlockOrdering;
  for (std::size_t i = 0; i < vars_.size(); ++i)
    if (problem.HasParameterBlock(values[i].data())) ordering->AddElementToGroup(values[i].data(), vars_[i].eliminate_first ? 0 : 1);
  o.linear_solver_ordering.reset(ordering);
  ceres::Solver::Summary s;
  ceres::Solve(o, &problem, &s);
  if (out) *out = report(s);
  return values;
}

double FactorGraph::residualNorm(int id) const {
  const Factor& f = factors_[id];
  std::vector<const double*> blocks;
  for (int v : f.vars) blocks.push_back(vars_[v].value.data());
  std::vector<double> r(f.cost->num_residuals());
  if (!f.cost->Evaluate(blocks.data(), r.data(), nullptr)) return std::numeric_limits<double>::infinity();
  double s = 0;
  for (double x : r) s += x * x;
  return std::sqrt(s);
}

int FactorGraph::residualCount(int id) const { return factors_[id].cost->num_residuals(); }

FactorGraph::Values FactorGraph::values() const {
  Values out(vars_.size());
  for (std::size_t i = 0; i < vars_.size(); ++i) out[i] = vars_[i].value;
  return out;
}

double FactorGraph::cost() const {
  // As Ceres counts it: half the sum of each block's (robust) squared norm.
  double c = 0;
  for (std::size_t id = 0; id < factors_.size(); ++id) {
    const Factor& f = factors_[id];
    if (f.removed) continue;
    const double n = residualNorm(static_cast<int>(id));
    double rho[3] = {n * n, 1, 0};
    if (const ceres::LossFunction* loss = lossFor(f)) loss->Evaluate(n * n, rho);
    c += 0.5 * rho[0];
  }
  return c;
}

}  // namespace slide::backend
