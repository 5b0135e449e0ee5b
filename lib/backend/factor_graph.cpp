#include "backend/factor_graph.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <limits>
#include <cmath>
#include <stdexcept>

#include "backend/factors.h"

namespace slide {

namespace {
int blockSize(BlockKind k) { return k == BlockKind::Vector3 ? 3 : 7; }

ceres::Problem::Options sharedOptions() {
  ceres::Problem::Options o;
  o.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  o.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  o.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  return o;
}

SolveReport report(const ceres::Solver::Summary& s) {
  SolveReport r;
  r.initial_cost = s.initial_cost;
  r.final_cost = s.final_cost;
  r.iterations = static_cast<int>(s.iterations.size());
  r.residual_blocks = s.num_residual_blocks;
  r.message = s.message;
  return r;
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
      cylinder_manifold_(newCylinderManifold()) {
  ceres::Problem::Options o = sharedOptions();
  o.enable_fast_removal = true;
  global_ = std::make_unique<ceres::Problem>(o);
}

FactorGraph::~FactorGraph() { global_.reset(); }

FactorGraph::FactorGraph(FactorGraph&&) noexcept = default;

FactorGraph& FactorGraph::operator=(FactorGraph&& o) noexcept {
  if (this == &o) return *this;
  global_.reset();  // before the blocks and cost functions it points to go
  vars_ = std::move(o.vars_);
  factors_ = std::move(o.factors_);
  removed_ = o.removed_;
  robust_scale_ = o.robust_scale_;
  losses_ = std::move(o.losses_);
  pose_manifold_ = std::move(o.pose_manifold_);
  cylinder_manifold_ = std::move(o.cylinder_manifold_);
  global_ = std::move(o.global_);
  return *this;
}

ceres::Manifold* FactorGraph::manifoldFor(BlockKind kind) const {
  switch (kind) {
    case BlockKind::Pose: return pose_manifold_.get();
    case BlockKind::Cylinder: return cylinder_manifold_.get();
    case BlockKind::Vector3: return nullptr;
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
  const int id = static_cast<int>(vars_.size()) - 1;
  global_->AddParameterBlock(vars_[id].value.data(), blockSize(kind), manifoldFor(kind));
  return id;
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
    losses_[n] = std::make_unique<ceres::HuberLoss>(a);
  }
  std::vector<double*> blocks;
  for (int v : f.vars) blocks.push_back(vars_[v].value.data());
  f.global_id = global_->AddResidualBlock(f.cost.get(), lossFor(f), blocks);
  const int id = static_cast<int>(factors_.size());
  for (int v : f.vars) vars_[v].factors.push_back(id);
  factors_.push_back(std::move(f));
  return id;
}

void FactorGraph::removeFactor(int id) {
  Factor& f = factors_[id];
  if (f.removed) return;
  global_->RemoveResidualBlock(static_cast<ceres::ResidualBlockId>(f.global_id));
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
  global_->RemoveParameterBlock(v.value.data());
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
  ceres::Solver::Options o = fullOptions(max_iterations, function_tolerance, num_threads, trust_region_radius);
  auto* ordering = new ceres::ParameterBlockOrdering;
  for (auto& v : vars_)
    if (!v.removed) ordering->AddElementToGroup(v.value.data(), v.eliminate_first ? 0 : 1);
  o.linear_solver_ordering.reset(ordering);
  ceres::Solver::Summary s;
  ceres::Solve(o, global_.get(), &s);
  return report(s);
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
  double c = 0;
  global_->Evaluate(ceres::Problem::EvaluateOptions(), &c, nullptr, nullptr, nullptr);
  return c;
}

}  // namespace slide
