#include "scenario_run.h"

#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <thread>

#include "backend/optimizer.h"
#include "clock/thread_cpu.h"
#include "eval/ate.h"

#include <spdlog/spdlog.h>

namespace slide {

namespace {
using Clock = std::chrono::steady_clock;

Pose perturb(const Pose& T, double metres, double degrees, std::mt19937& rng) {
  std::normal_distribution<double> g(0, 1);
  const Pose D = poseFromXyzYaw(metres * g(rng), metres * g(rng), 0.3 * metres * g(rng), degrees * M_PI / 180 * g(rng));
  return T * D;
}

// Estimated poses of every robot next to the true ones (in the host's frame).
struct Pairs {
  std::vector<Pose> est, ref;
};

void collect(const graph_scenario::GraphScenario& s, const std::map<int, std::vector<backend::TrajectoryPose>>& est,
             Pairs& out) {
  const Pose host0_inv = s.robots[0].truth.front().inverse();
  for (const graph_scenario::ScenarioRobot& r : s.robots) {
    const auto it = est.find(r.id);
    if (it == est.end()) continue;
    for (const backend::TrajectoryPose& p : it->second) {
      out.est.push_back(p.pose);
      out.ref.push_back(host0_inv * r.truth[p.seq]);
    }
  }
}

double landmarkError(const Object& est, const Object& truth) {
  if (est.shape() == Shape::Cylinder && truth.shape() == Shape::Cylinder)
    return (std::get<Cylinder>(est.model).root - std::get<Cylinder>(truth.model).root).head<2>().norm();
  return (est.position() - truth.position()).norm();
}

// Detections not of their landmark's majority true object, over all detections (votes: landmark
// id -> true object index -> detections; the simulator's associations).
double wrongAssociationFraction(const std::map<std::int64_t, std::map<int, int>>& votes) {
  int total = 0, wrong = 0;
  for (const auto& [id, counts] : votes) {
    int best = 0, sum = 0;
    for (const auto& [i, c] : counts) best = std::max(best, c), sum += c;
    total += sum;
    wrong += sum - best;
  }
  return total ? static_cast<double>(wrong) / total : 0.0;
}
}  // namespace

ScenarioRunResult runScenario(const graph_scenario::GraphScenario& s, const backend::BackendConfig& cfg,
                              bool with_batch, double pace_hz, double final_seconds, int progress_every) {
  ScenarioRunResult out;
  backend::Optimizer opt(cfg, ClassTable::loadDefault(), s.robots[0].id);
  std::mt19937 rng(11);
  std::map<std::int64_t, std::map<int, int>> votes;  // landmark id -> true index -> count
  std::size_t longest = 0;
  for (const auto& r : s.robots) longest = std::max(longest, r.bundles.size());
  std::map<int, Pose> given;  // last transform given per peer
  std::map<int, std::map<int, std::vector<graph_scenario::ScenarioLoopClosure>>>
      closures;  // robot -> seq_b -> closures
  for (const auto& r : s.robots)
    for (const auto& lc : graph_scenario::simulateLoopClosures(r)) closures[r.id][lc.seq_b].push_back(lc);
  int objects = 0;
  std::function<void(std::size_t)> progress;
  std::size_t inserted = 0;  // host key poses so far
  auto tally = [&](const backend::UpdateResult& u) {
    if (!u.full_solve) return;
    ++out.full_solves;
    out.full_solve_ms.push_back(u.full_solve_ms);
    if (progress && spdlog::should_log(spdlog::level::debug)) progress(inserted);
  };
  // Long missions: the live estimate so far against the truth and against odometry, every
  // progress_every key poses (info) and after every full solve taken in (debug).
  if (progress_every > 0) progress = [&](std::size_t done) {
    Pairs live, odom;
    for (const backend::TrajectoryPose& p : opt.trajectory(s.robots[0].id)) {
      live.est.push_back(p.pose);
      live.ref.push_back(s.robots[0].truth[p.seq]);
      odom.est.push_back(s.robots[0].bundles[p.seq].odom_pose);
      odom.ref.push_back(s.robots[0].truth[p.seq]);
    }
    const double ate = eval::absoluteTrajectoryError(live.est, live.ref, eval::TrajectoryAlignment::Se3).rmse;
    const double odo = eval::absoluteTrajectoryError(odom.est, odom.ref, eval::TrajectoryAlignment::Se3).rmse;
    spdlog::log(done % progress_every == 0 ? spdlog::level::info : spdlog::level::debug,
                "key pose {} of {}: live ATE {:.2f} m, odometry {:.2f} m (ratio {:.3f}), wrong associations {:.2f} %, "
                "{} full solves, {} loop closures (against the simulator's truth)",
                done, longest, ate, odo, ate / std::max(1e-9, odo), 100.0 * wrongAssociationFraction(votes), out.full_solves,
                out.loop_closures);
  };
  auto last_input = Clock::now();
  auto pace = [&]() {
    if (pace_hz > 0 && opt.solving())
      std::this_thread::sleep_until(last_input + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / pace_hz)));
    last_input = Clock::now();
  };
  for (std::size_t k = 0; k < longest; ++k) {
    for (const graph_scenario::ScenarioRobot& r : s.robots) {
      if (k >= r.bundles.size()) continue;
      pace();
      const double c0 = clock::threadCpuMs();
      const backend::UpdateResult u = opt.addBundle(r.bundles[k]);
      const double cpu = clock::threadCpuMs() - c0;
      objects += static_cast<int>(r.bundles[k].objects.size());
      if (!u.accepted) ++out.rejected;
      if (!u.held) {
        out.update_ms.push_back(u.update_ms);
        out.update_cpu_ms.push_back(cpu);
      }
      if (r.id == s.robots[0].id) inserted = k + 1;
      tally(u);
      if (progress_every > 0 && r.id == s.robots[0].id && (k + 1) % progress_every == 0) progress(k + 1);
      for (std::size_t i = 0; i < u.landmark_ids.size(); ++i)
        if (u.landmark_ids[i] >= 0) ++votes[u.landmark_ids[i]][r.seen[k][i]];
      if (!opt.merged(r.id)) continue;
      for (const graph_scenario::ScenarioLoopClosure& lc : closures[r.id][static_cast<int>(k)]) {
        pace();
        out.loops_during_solve += opt.solving();
        const double c1 = clock::threadCpuMs();
        const backend::UpdateResult l = opt.addLoopClosure(lc.robot, lc.seq_a, lc.seq_b, lc.T_a_b);
        out.update_cpu_ms.push_back(clock::threadCpuMs() - c1);
        out.update_ms.push_back(l.update_ms);
        tally(l);
        ++out.loop_closures;
        spdlog::debug("loop closure {} -> {} (robot {}){}", lc.seq_a, lc.seq_b, lc.robot, l.accepted ? "" : ": " + l.reason);
      }
    }
    for (std::size_t p = 1; p < s.robots.size(); ++p) {
      const bool first = k == longest / 2, refine = k == 3 * longest / 4;
      if (!first && !refine) continue;
      const Pose truth = s.robots[0].truth.front().inverse() * s.robots[p].truth.front();
      given[s.robots[p].id] = first ? perturb(truth, 0.3, 1.0, rng) : perturb(truth, 0.05, 0.2, rng);
      const double c0 = clock::threadCpuMs();
      const backend::UpdateResult u = opt.addRobotTransform(s.robots[p].id, given[s.robots[p].id]);
      out.update_cpu_ms.push_back(clock::threadCpuMs() - c0);
      // Ids of landmarks the merged bundles joined are not reported per object; votes come
      // from later updates.
      out.update_ms.push_back(u.update_ms);
      tally(u);
    }
  }
  {
    std::map<int, std::vector<backend::TrajectoryPose>> live;
    for (int r : opt.robots()) live[r] = opt.trajectory(r);
    Pairs pairs;
    collect(s, live, pairs);
    out.live_ate_m = eval::absoluteTrajectoryError(pairs.est, pairs.ref, eval::TrajectoryAlignment::Se3).rmse;
    for (const graph_scenario::ScenarioRobot& r : s.robots) {
      const auto it = live.find(r.id);
      if (it == live.end()) continue;
      for (std::size_t k = 1; k < it->second.size(); ++k) {
        const backend::TrajectoryPose &a = it->second[k - 1], &b = it->second[k];
        const Pose est = a.pose.inverse() * b.pose, truth = r.truth[a.seq].inverse() * r.truth[b.seq];
        out.live_max_step_error_m = std::max(out.live_max_step_error_m, (est.translation() - truth.translation()).norm());
      }
    }
  }
  const auto t0 = Clock::now();
  const double c0 = clock::threadCpuMs();
  opt.fullSolve(final_seconds);
  out.final_solve_cpu_ms = clock::threadCpuMs() - c0;
  out.final_solve_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  out.incremental_cost = opt.cost();
  out.keyposes = opt.numKeyPoses();
  out.objects_per_keypose = static_cast<double>(objects) / std::max(1, out.keyposes);

  std::map<int, std::vector<backend::TrajectoryPose>> est;
  for (int r : opt.robots()) est[r] = opt.trajectory(r);
  Pairs pairs;
  collect(s, est, pairs);
  const eval::AteResult ate = eval::absoluteTrajectoryError(pairs.est, pairs.ref, eval::TrajectoryAlignment::Se3);
  out.ate_m = ate.rmse;

  // Raw odometry, each robot placed by the transform it was given.
  Pairs odom;
  for (const graph_scenario::ScenarioRobot& r : s.robots) {
    const Pose T = r.id == s.robots[0].id ? Pose::Identity() : given.count(r.id) ? given[r.id] : Pose::Identity();
    if (r.id != s.robots[0].id && !given.count(r.id)) continue;
    for (std::size_t k = 0; k < r.bundles.size(); ++k) {
      odom.est.push_back(T * r.bundles[k].odom_pose);
      odom.ref.push_back(s.robots[0].truth.front().inverse() * r.truth[k]);
    }
  }
  out.odom_ate_m = eval::absoluteTrajectoryError(odom.est, odom.ref, eval::TrajectoryAlignment::Se3).rmse;

  // Landmarks: each confirmed one against the true landmark most of its detections came from.
  const std::vector<Object> lms = opt.landmarks(true);
  out.landmarks = static_cast<int>(lms.size());
  double sq = 0;
  int n = 0;
  const Pose host_to_world = s.robots[0].truth.front();
  std::map<int, int> confirmed_per_object;  // true object -> confirmed landmarks it is the majority of
  for (const Object& lm : lms) {
    const auto it = votes.find(lm.id);
    if (it == votes.end()) continue;
    int best = -1, count = 0;
    for (const auto& [i, c] : it->second)
      if (c > count) best = i, count = c;
    ++confirmed_per_object[best];
    const double e = landmarkError(transformObject(host_to_world * ate.alignment.T, lm), s.landmarks[best]);
    sq += e * e;
    ++n;
  }
  out.landmark_rmse_m = n ? std::sqrt(sq / n) : 0;
  int duplicates = 0;
  for (const auto& [i, c] : confirmed_per_object) duplicates += c - 1;
  out.duplicate_fraction = lms.empty() ? 0.0 : static_cast<double>(duplicates) / lms.size();
  out.wrong_association_fraction = wrongAssociationFraction(votes);
  std::vector<char> seen(s.landmarks.size(), 0);
  for (const auto& r : s.robots)
    for (const auto& list : r.seen)
      for (int i : list) seen[i] = 1;
  for (char c : seen) out.true_landmarks_seen += c;

  if (with_batch) {
    const double cb = clock::threadCpuMs();
    const backend::Optimizer::Batch b = opt.solveBatch();
    out.batch_cpu_ms = clock::threadCpuMs() - cb;
    out.batch_ms = b.ms;
    out.batch_cost = b.report.final_cost;
    Pairs bp;
    collect(s, b.trajectories, bp);
    out.batch_ate_m = eval::absoluteTrajectoryError(bp.est, bp.ref, eval::TrajectoryAlignment::Se3).rmse;
  }
  return out;
}

}  // namespace slide
