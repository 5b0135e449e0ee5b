// Full solves of the optimizer: on a snapshot of the graph, in the calling thread or on the
// background worker, and how a solution made while the graph grew is taken in.
#include <algorithm>
#include <chrono>
#include <map>
#include <unordered_map>

#include "backend/optimizer.h"
#include "backend/factors.h"
#include "backend/loop_spread.h"
#include "backend/pose_block.h"
#include "backend/solve_worker.h"

namespace slide::backend {

// One full solve: the snapshot it works on, and what taking its solution in needs to know of
// the graph as it was then (each robot's last key pose).
struct Optimizer::FullSolveJob {
  FactorGraph::Snapshot snapshot;
  FactorGraph::FullSolveOptions options;
  bool update_path = true;  // taken in by an update or poll(): outliers, duplicates and guard follow it
  int epoch = 0;
  struct RobotEnd {
    int robot;
    std::size_t count;  // key poses of the robot then
    int var;            // the last one's variable
  };
  std::vector<RobotEnd> ends;
  // Loop closures it brings: in its snapshot only, spread along their loops before the solve,
  // added to the graph when its solution is taken in (queued again when it is not).
  std::vector<PendingLoop> loops;
  std::vector<LoopSpread> spreads;
  // For the spreads: the live landmarks' variables and shapes, and which variables are key
  // poses (their observers are found in the snapshot's terms on the worker, off the update path).
  std::vector<std::pair<int, Shape>> landmarks;
  std::vector<char> keypose;
  PoseSigma loop_sigma;
  LoopSpreadNoise spread_noise;
  std::vector<double> residual_norms;
  SolveReport report;

  void run(const std::atomic<bool>* cancel) {
    if (!spreads.empty()) spreadLoops(snapshot.values, spreads, observersOf(), loop_sigma, spread_noise);
    options.cancel = cancel;
    report = FactorGraph::solveSnapshot(snapshot, options, update_path ? &residual_norms : nullptr);
  }

  // Each landmark's observers: the key poses its terms in the snapshot tie it to.
  std::vector<LandmarkObservers> observersOf() const {
    std::vector<int> index(snapshot.values.size(), -1);
    std::vector<LandmarkObservers> out(landmarks.size());
    for (std::size_t k = 0; k < landmarks.size(); ++k) {
      const auto [var, shape] = landmarks[k];
      out[k].var = var, out[k].shape = shape;
      if (var >= 0 && var < static_cast<int>(index.size())) index[var] = static_cast<int>(k);
    }
    for (const FactorGraph::Snapshot::Term& t : snapshot.terms) {
      int lm = -1, pose = -1;
      for (int j = t.first; j < t.first + t.count; ++j) {
        const int v = snapshot.vars[j];
        if (v < 0 || v >= static_cast<int>(index.size())) continue;
        if (index[v] >= 0) lm = index[v];
        else if (v < static_cast<int>(keypose.size()) && keypose[v]) pose = v;
      }
      if (lm >= 0 && pose >= 0) out[lm].observers.push_back(pose);
    }
    return out;
  }
};

Vector6d Optimizer::loopSigma() const {
  PoseSigma s;
  s << cfg_.loop_translation_sigma, cfg_.loop_translation_sigma, cfg_.loop_translation_sigma, cfg_.loop_rotation_sigma,
      cfg_.loop_rotation_sigma, cfg_.loop_rotation_sigma;
  return s;
}

bool Optimizer::solving() const { return running_ || (worker_ && worker_->busy()); }

void Optimizer::cancelSolve() {
  if (!running_) return;
  worker_->cancel();
  requeueLoops(*running_);
  running_.reset();
}

void Optimizer::requeueLoops(const FullSolveJob& job) {
  if (job.epoch != epoch_ || job.loops.empty()) return;  // a rebuild replayed them
  std::vector<PendingLoop> back;  // before those that came since, unless one repeats it
  for (const PendingLoop& l : job.loops)
    if (std::none_of(pending_loops_.begin(), pending_loops_.end(), [&](const PendingLoop& p) {
          return p.robot == l.robot && p.seq_a == l.seq_a && p.seq_b == l.seq_b;
        }))
      back.push_back(l);
  pending_loops_.insert(pending_loops_.begin(), back.begin(), back.end());
  pending_iterations_ = std::max(pending_iterations_, cfg_.loop_iterations);
}

bool Optimizer::requestFull(int iterations, UpdateResult& r) {
  pending_iterations_ = std::max(pending_iterations_, iterations);
  const bool inline_solve = !background();
  startPending(r);
  return inline_solve;
}

void Optimizer::takePendingLoops(FullSolveJob& job) {
  job.loop_sigma = loopSigma();
  job.spread_noise = {cfg_.odom_translation_floor, cfg_.odom_translation_per_m, cfg_.odom_rotation_floor,
                      cfg_.odom_rotation_per_m};
  std::map<int, int> oldest;  // robot -> oldest key pose (seq) a new closure of it reaches
  for (const PendingLoop& l : pending_loops_) {
    const KeyPose* a = findKeyPose(l.robot, l.seq_a);
    const KeyPose* b = findKeyPose(l.robot, l.seq_b);
    if (!a || !b) continue;  // checked on arrival; key poses are never removed
    job.loops.push_back(l);
    FactorGraph::addToSnapshot(job.snapshot, relativePoseFactor(l.T_a_b, job.loop_sigma), {a->var, b->var});
    const int first = std::min(l.seq_a, l.seq_b);
    const auto it = oldest.find(l.robot);
    if (it == oldest.end() || first < it->second) oldest[l.robot] = first;
  }
  pending_loops_.clear();
  if (!cfg_.spread_loops || oldest.empty()) return;
  for (const auto& [robot, first] : oldest) {
    const std::vector<int>& list = robots_[robot].keyposes;
    auto position = [&](int seq) {
      return static_cast<int>(std::lower_bound(list.begin(), list.end(), seq,
                                               [&](int kp, int s) { return keyposes_[kp].seq < s; }) - list.begin());
    };
    const int start = position(first);
    LoopSpread spread;
    for (std::size_t k = start; k < list.size(); ++k) spread.chain.push_back(keyposes_[list[k]].var);
    std::map<int, int> fixed_index;  // list position before the chain -> -(k + 1)
    auto index = [&](int seq) {
      const int p = position(seq);
      if (p >= start) return p - start;
      const auto [it, added] = fixed_index.emplace(p, -static_cast<int>(spread.fixed.size()) - 1);
      if (added) spread.fixed.push_back(keyposes_[list[p]].var);
      return it->second;
    };
    auto add = [&](int seq_a, int seq_b, const Pose& T) {
      if (std::max(seq_a, seq_b) < first) return;  // wholly before the chain: nothing there moves
      spread.closures.push_back({index(seq_a), index(seq_b), T});
    };
    for (const PendingLoop& l : job.loops)
      if (l.robot == robot) add(l.seq_a, l.seq_b, l.T_a_b);
    for (const auto& [key, factor] : loop_factors_)
      if (key.first == robot) add(key.second.first, key.second.second, factor.T_a_b);
    job.spreads.push_back(std::move(spread));
  }
  job.landmarks.reserve(landmarks_.size());
  for (const Landmark& lm : landmarks_)
    if (lm.alive && !lm.seen.empty()) job.landmarks.emplace_back(lm.var, lm.shape);
  job.keypose.assign(job.snapshot.values.size(), 0);
  for (const KeyPose& kp : keyposes_)
    if (kp.var >= 0 && kp.var < static_cast<int>(job.keypose.size())) job.keypose[kp.var] = 1;
}

void Optimizer::addLoopFactors(const FullSolveJob& job) {
  for (const PendingLoop& l : job.loops) {
    const KeyPose* a = findKeyPose(l.robot, l.seq_a);
    const KeyPose* b = findKeyPose(l.robot, l.seq_b);
    const auto key = std::make_pair(l.robot, std::make_pair(l.seq_a, l.seq_b));
    const auto it = loop_factors_.find(key);
    if (it != loop_factors_.end()) graph_.removeFactor(it->second.factor);  // repeated while the solve ran
    loop_factors_[key] = {graph_.addFactor(relativePoseFactor(l.T_a_b, job.loop_sigma), {a->var, b->var}, false), l.T_a_b};
    std::vector<Span>& ties = robots_[l.robot].ties;
    if (std::find(ties.begin(), ties.end(), Span{a->index, b->index}) == ties.end()) ties.emplace_back(a->index, b->index);
  }
}

std::shared_ptr<Optimizer::FullSolveJob> Optimizer::makeJob(int iterations, double function_tolerance) {
  auto job = std::make_shared<FullSolveJob>();
  for (const PendingLoop& l : pending_loops_) {  // a repeated closure replaces the one in the graph
    const auto it = loop_factors_.find({l.robot, {l.seq_a, l.seq_b}});
    if (it == loop_factors_.end()) continue;
    graph_.removeFactor(it->second.factor);
    loop_factors_.erase(it);
  }
  job->snapshot = graph_.snapshot();
  takePendingLoops(*job);
  job->options.max_iterations = iterations;
  job->options.function_tolerance = function_tolerance;
  job->options.num_threads = cfg_.num_threads;
  job->options.trust_region_radius = cfg_.full_trust_region_radius;
  job->epoch = epoch_;
  for (const auto& [id, robot] : robots_)
    if (!robot.keyposes.empty()) {
      const KeyPose& last = keyposes_[robot.keyposes.back()];
      job->ends.push_back({id, robot.keyposes.size(), last.var});
    }
  full_pending_ = false;
  last_full_step_ = step_;
  return job;
}

void Optimizer::startPending(UpdateResult& r) {
  if (pending_iterations_ == 0 || solving()) return;
  const bool converge = pending_iterations_ >= cfg_.final_iterations;  // settle()
  std::shared_ptr<FullSolveJob> job =
      makeJob(pending_iterations_, converge ? cfg_.final_function_tolerance : cfg_.full_function_tolerance);
  pending_iterations_ = 0;
  if (!background()) {
    job->run(stop_flag_);
    adopt(*job, r);
    return;
  }
  if (!worker_) worker_ = std::make_unique<SolveWorker>();
  const auto task = [job, hook = solve_hook_](const std::atomic<bool>& cancel) {
    if (hook) hook();
    job->run(&cancel);
  };
  if (worker_->start(task)) running_ = job;
}

void Optimizer::yieldToLoop() {
  if (running_ && running_->loops.empty()) cancelSolve();
}

bool Optimizer::poll(UpdateResult* out) {
  if (running_ && worker_->busy()) return false;
  UpdateResult local;
  UpdateResult& r = out ? *out : local;
  bool taken = false;
  if (running_) {
    const std::shared_ptr<FullSolveJob> job = std::move(running_);
    taken = adopt(*job, r);
  }
  startPending(r);  // a loop closure or merge that came while it ran (or once a cancelled one ended)
  return taken;
}

bool Optimizer::adopt(FullSolveJob& job, UpdateResult& r) {
  if (job.epoch != epoch_) return false;
  if (job.report.aborted) {
    requeueLoops(job);
    return false;
  }
  addLoopFactors(job);
  const FactorGraph::Snapshot& s = job.snapshot;
  // Key poses added meanwhile keep their pose relative to their robot's last key pose of the
  // snapshot as it is now (local solves have moved it since), and follow it to its solution;
  // landmarks made meanwhile follow their first observer.
  std::vector<Pose> anchors;
  for (const FullSolveJob::RobotEnd& e : job.ends) anchors.push_back(poseOf(e.var));
  for (std::size_t v = 0; v < s.values.size(); ++v)
    if (!s.removed[v] && !graph_.removedVariable(static_cast<int>(v))) graph_.setValue(static_cast<int>(v), s.values[v].data());
  std::unordered_map<int, Pose> moved;
  for (std::size_t i = 0; i < job.ends.size(); ++i) {
    const FullSolveJob::RobotEnd& e = job.ends[i];
    const std::vector<int>& list = robots_[e.robot].keyposes;
    if (list.size() <= e.count) continue;
    const Pose C = poseOf(e.var) * anchors[i].inverse();
    for (std::size_t k = e.count; k < list.size(); ++k) {
      const int var = keyposes_[list[k]].var;
      const PoseBlock block = toPoseBlock(C * poseOf(var));
      graph_.setValue(var, block.data());
      moved.emplace(var, C);
    }
  }
  if (!moved.empty())
    for (const Landmark& lm : landmarks_) {
      if (!lm.alive || lm.seen.empty() || lm.var < static_cast<int>(s.values.size())) continue;
      const auto it = moved.find(lm.seen.front().pose_var);
      if (it != moved.end()) moveLandmarkBlock(graph_.value(lm.var), lm.shape, it->second);
    }
  afterSolve({}, true);
  if (job.update_path && detachOutliers(&job.residual_norms) + mergeDuplicates() > 0) afterSolve({}, true);
  r.full_solve = true;
  r.full_solve_ms = job.report.wall_ms;
  r.solve = job.report;
  if (job.update_path) guard(r);
  return true;
}

SolveReport Optimizer::settle() {
  if (!background()) return fullSolve(0, true);
  pending_iterations_ = std::max(pending_iterations_, cfg_.final_iterations);
  UpdateResult r;
  startPending(r);
  return r.solve;
}

namespace {
constexpr int kSettleIterations = 10;  // each later round of a solve to convergence
}  // namespace

SolveReport Optimizer::fullSolve(double max_seconds, bool interruptible) {
  cancelSolve();
  pending_iterations_ = 0;
  const auto t0 = std::chrono::steady_clock::now();
  auto left = [&]() {
    return max_seconds - std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  UpdateResult r;
  SolveReport s;
  for (int round = 0; round < 4; ++round) {
    if (round > 0 && (detachOutliers() + mergeDuplicates() == 0 || (max_seconds > 0 && left() <= 0))) break;
    // Later rounds start from the converged estimate with a few observations detached or merged:
    // a short warm solve takes that local change (run to 1e-10 they crept on for the whole budget,
    // 20-80 s each at 3,000 key poses).
    std::shared_ptr<FullSolveJob> job =
        round == 0 ? makeJob(cfg_.final_iterations, cfg_.final_function_tolerance)
                   : makeJob(std::min(cfg_.final_iterations, kSettleIterations), cfg_.full_function_tolerance);
    job->update_path = false;  // outliers, duplicates and the guard follow below
    if (max_seconds > 0) job->options.max_seconds = std::max(1e-3, left());
    job->run(interruptible ? stop_flag_ : nullptr);
    adopt(*job, r);
    s = job->report;
    if (s.aborted) return s;
  }
  if (max_seconds > 0) {
    std::string why;
    if (cfg_.guard_estimate && robotOutsideEnvelope(&why) >= 0) {
      s.aborted = true;
      s.message = "estimate outside the odometry envelope: " + why;
    }
    return s;
  }
  const int before = unmerged_;
  guard(r);
  if (unmerged_ != before) return fullSolve(0, interruptible);
  return s;
}

}  // namespace slide::backend
