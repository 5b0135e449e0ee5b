#include "realistic_run.h"

#include <cmath>
#include <map>
#include <memory>

#include <spdlog/spdlog.h>

#include "backend/optimizer.h"
#include "clock/thread_cpu.h"
#include "eval/alignment.h"
#include "eval/ate.h"
#include "eval/transform_error.h"

namespace slide {

namespace {
// One robot's own stack: its optimizer (own bundles only; the host's also takes the peers')
// and its loop closer.
struct Stack {
  std::unique_ptr<backend::Optimizer> optimizer;
  std::unique_ptr<place::LoopCloser> closer;
};

std::vector<place::KeyPose> keyPoses(const backend::Optimizer& opt, int robot) {
  std::vector<place::KeyPose> out;
  for (const backend::TrajectoryPose& p : opt.trajectory(robot)) out.push_back({p.seq, p.pose});
  return out;
}

using Votes = std::map<std::int64_t, std::map<int, int>>;  // landmark id -> true index (-1: false object) -> count

int majority(const Votes& votes, std::int64_t id) {
  const auto it = votes.find(id);
  int best = -1, count = 0;
  if (it != votes.end())
    for (const auto& [i, c] : it->second)
      if (c > count) best = i, count = c;
  return best;
}

// The truth for a transform between two bent maps: the least-squares rigid motion (x, y, z,
// yaw) taking B's objects onto A's over the true objects both maps hold (identified by the
// simulator's object ids, for scoring only); nullopt when they share fewer than 3.
// With `near`, over those of A's objects within `radius` (horizontally) of it only.
std::optional<Pose> mapAlignmentTruth(const ObjectMap& a, const Votes& va, const ObjectMap& b, const Votes& vb,
                                      const std::optional<Eigen::Vector3d>& near = std::nullopt, double radius = 0) {
  std::map<int, Eigen::Vector3d> in_a;
  for (const Object& o : a.objects())
    if (const int t = majority(va, o.id); t >= 0 && (!near || (o.position() - *near).head<2>().norm() < radius))
      in_a[t] = o.position();
  std::vector<Eigen::Vector3d> pa, pb;
  for (const Object& o : b.objects())
    if (const int t = majority(vb, o.id); t >= 0 && in_a.count(t)) {
      pa.push_back(in_a[t]);
      pb.push_back(o.position());
    }
  if (pa.size() < 3) return std::nullopt;
  return eval::align(pb, pa, eval::TrajectoryAlignment::Yaw4Dof).T;
}

// The host's ATE (SE3-aligned) over the key poses it holds so far; with `odometry`, its
// odometry's over the same key poses.
double hostAteSoFar(const backend::Optimizer& opt, const graph_scenario::ScenarioRobot& r, bool odometry = false) {
  std::vector<Pose> est, ref;
  for (const backend::TrajectoryPose& p : opt.trajectory(r.id)) {
    est.push_back(odometry ? r.bundles[p.seq].odom_pose : p.pose);
    ref.push_back(r.truth[p.seq]);
  }
  return est.size() < 3 ? 0.0 : eval::absoluteTrajectoryError(est, ref, eval::TrajectoryAlignment::Se3).rmse;
}

double horizontalError(const Object& est, const Object& truth) {
  if (est.shape() == Shape::Cylinder && truth.shape() == Shape::Cylinder)
    return (std::get<Cylinder>(est.model).root - std::get<Cylinder>(truth.model).root).head<2>().norm();
  return (est.position() - truth.position()).norm();
}
}  // namespace

RealisticRunResult runRealistic(const graph_scenario::GraphScenario& s, const backend::BackendConfig& cfg,
                                const place::LoopCloserParams& closer, double period_s, int map_every) {
  RealisticRunResult out;
  const ClassTable classes = ClassTable::loadDefault();
  const int host = s.robots[0].id;
  std::map<int, Stack> stacks;
  for (const graph_scenario::ScenarioRobot& r : s.robots) {
    place::LoopCloserParams p = closer;
    p.robot = r.id;
    stacks[r.id] = {std::make_unique<backend::Optimizer>(cfg, classes, r.id), std::make_unique<place::LoopCloser>(p)};
  }
  backend::Optimizer& opt = *stacks[host].optimizer;
  out.peers = static_cast<int>(s.robots.size()) - 1;
  std::map<int, Votes> votes;             // per robot's optimizer
  std::map<int, ObjectMap> published;     // each robot's own map as last given to the loop closers
  std::map<int, Pose> given;                         // last transform given per peer
  std::size_t longest = 0;
  for (const auto& r : s.robots) longest = std::max(longest, r.bundles.size());
  auto timed = [&](auto&& update) {
    const double c0 = clock::threadCpuMs();
    const backend::UpdateResult u = update();
    if (!u.held) {
      out.update_ms.push_back(u.update_ms);
      out.update_cpu_ms.push_back(clock::threadCpuMs() - c0);
    }
    return u;
  };
  for (std::size_t k = 0; k < longest; ++k) {
    for (const graph_scenario::ScenarioRobot& r : s.robots) {
      if (k >= r.bundles.size()) continue;
      auto vote = [&](const backend::UpdateResult& u, Votes& v) {
        for (std::size_t i = 0; i < u.landmark_ids.size() && i < r.seen[k].size(); ++i)
          if (u.landmark_ids[i] >= 0) ++v[u.landmark_ids[i]][r.seen[k][i]];
      };
      vote(timed([&] { return opt.addBundle(r.bundles[k]); }), votes[host]);
      if (r.id != host) vote(stacks[r.id].optimizer->addBundle(r.bundles[k]), votes[r.id]);
    }
    if ((k + 1) % 50 == 0)
      out.ate_trace.push_back({static_cast<int>(k + 1), hostAteSoFar(opt, s.robots[0]), hostAteSoFar(opt, s.robots[0], true)});
    const double now = static_cast<double>(k) * period_s;
    if (k % map_every == 0 || k + 1 == longest) {
      for (auto& [id, st] : stacks) {
        const ObjectMap& own = published[id] = ObjectMap(st.optimizer->ownLandmarks());
        st.closer->setOwnMap(own, now);
        st.closer->setTrajectory(keyPoses(*st.optimizer, id));
        if (id != host) stacks[host].closer->setPeerMap(id, own, now);
      }
    }
    for (auto& [id, st] : stacks) {
      const double c0 = clock::threadCpuMs();
      const std::vector<place::LoopClosure> found = st.closer->poll(now);
      out.place_cpu_s += (clock::threadCpuMs() - c0) / 1000.0;
      if (id == host && found.empty() && !st.closer->lastReason().empty())
        spdlog::debug("key pose {}: host loop closer: {}", k, st.closer->lastReason());
      for (const place::LoopClosure& lc : found)
        if (id == host && lc.robot_a == lc.robot_b)
          spdlog::debug("key pose {}: host loop closer: {} -> {} {} ({} inliers)", k, lc.keypose_a, lc.keypose_b,
                        place::outcomeName(lc.outcome), lc.inliers.size());
      for (const place::LoopClosure& lc : found) {
        if (lc.outcome == place::ConsensusFilter::Outcome::Pending) continue;
        if (lc.robot_a == lc.robot_b) {
          if (id != host) {
            st.optimizer->addLoopClosure(lc.robot_a, lc.keypose_a, lc.keypose_b, lc.T_a_b);
            continue;
          }
          const graph_scenario::ScenarioRobot& hr = s.robots[0];
          RealisticRunResult::IntraClosure c;
          c.seq_a = lc.keypose_a;
          c.seq_b = lc.keypose_b;
          const eval::TransformError e =
              eval::transformError(lc.T_a_b, hr.truth[c.seq_a].inverse() * hr.truth[c.seq_b]);
          c.error_m = e.translation_m;
          c.error_deg = e.rotation_deg;
          c.host_ate_m = hostAteSoFar(opt, hr);
          c.accepted = timed([&] { return opt.addLoopClosure(lc.robot_a, lc.keypose_a, lc.keypose_b, lc.T_a_b); }).accepted;
          const bool wrong = c.error_m > 1.0 || c.error_deg > 2.0;
          ++out.intra_closures;
          out.wrong_intra += wrong;
          out.intra_accepted += c.accepted;
          out.wrong_intra_accepted += wrong && c.accepted;
          out.intra.push_back(c);
        } else if (id == host && lc.robot_a == host) {
          const graph_scenario::ScenarioRobot* peer = nullptr;
          for (const graph_scenario::ScenarioRobot& r : s.robots)
            if (r.id == lc.robot_b) peer = &r;
          if (!peer) continue;
          const Pose frames = s.robots[0].truth.front().inverse() * peer->truth.front();
          const eval::TransformError f = eval::transformError(lc.T_a_b, frames);
          out.frame_error_m.push_back(f.translation_m);
          const std::optional<Pose> maps =
              mapAlignmentTruth(published[host], votes[host], published[lc.robot_b], votes[lc.robot_b]);
          if (maps) {
            const eval::TransformError e = eval::transformError(lc.T_a_b, *maps);
            out.map_error_m.push_back(e.translation_m);
            out.wrong_inter += e.translation_m > 1.0 || e.yaw_deg > 2.0;
          } else {
            ++out.wrong_inter;  // the maps hold no common object: a false positive
          }
          ++out.inter_transforms;
          given[lc.robot_b] = lc.T_a_b;
          // The place: the inliers' centroid in the host's map.
          Eigen::Vector3d centre = Eigen::Vector3d::Zero();
          int in_host = 0;
          for (const auto& [ia, ib] : lc.inliers)
            for (const Object& o : published[host].objects())
              if (o.id == ia) centre += o.position(), ++in_host;
          const std::optional<Pose> place =
              in_host ? mapAlignmentTruth(published[host], votes[host], published[lc.robot_b], votes[lc.robot_b],
                                          centre / in_host, RealisticRunResult::kPlaceRadius)
                      : std::nullopt;
          if (place) {
            const eval::TransformError e = eval::transformError(lc.T_a_b, *place);
            out.place_error_m.push_back(e.translation_m);
            out.wrong_inter_at_place += e.translation_m > 1.0 || e.yaw_deg > 2.0;
          } else {
            ++out.wrong_inter_at_place;
          }
          const backend::UpdateResult u = timed([&] { return opt.addRobotTransform(lc.robot_b, lc.T_a_b); });
          spdlog::debug("key pose {}: transform to robot {} ({} inliers): {:.2f} m from the maps' alignment, {:.2f} m "
                        "from the alignment at its place, {:.1f} m from the true frames; {}{}", k, lc.robot_b,
                        lc.inliers.size(), maps ? eval::transformError(lc.T_a_b, *maps).translation_m : -1.0,
                        place ? eval::transformError(lc.T_a_b, *place).translation_m : -1.0, f.translation_m,
                        u.accepted ? "accepted" : "refused: " + u.reason, opt.merged(lc.robot_b) ? "" : " (not merged)");
        }
      }
    }
  }
  opt.fullSolve();
  spdlog::debug("after the final solve: {} peers merged, {} merges undone", opt.numPeersMerged(), opt.unmerged());
  out.keyposes = opt.numKeyPoses();

  // Trajectories of the host and of the peers it merged, and their odometry placed by the
  // transforms it was given, against the truth in the host's frame.
  const Pose host0_inv = s.robots[0].truth.front().inverse();
  std::vector<Pose> est, ref, odom, odom_ref;
  for (const graph_scenario::ScenarioRobot& r : s.robots) {
    if (r.id != host && !opt.merged(r.id)) continue;
    out.peers_merged += r.id != host;
    for (const backend::TrajectoryPose& p : opt.trajectory(r.id)) {
      est.push_back(p.pose);
      ref.push_back(host0_inv * r.truth[p.seq]);
    }
    const Pose T = r.id == host ? Pose::Identity() : given.count(r.id) ? given[r.id] : Pose::Identity();
    {
      std::vector<Pose> e, t, o;
      for (const backend::TrajectoryPose& p : opt.trajectory(r.id)) {
        e.push_back(p.pose);
        t.push_back(host0_inv * r.truth[p.seq]);
        o.push_back(T * r.bundles[p.seq].odom_pose);
      }
      spdlog::debug("robot {}: {} key poses, ATE {:.2f} m, its odometry's {:.2f} m (each aligned alone)", r.id,
                    e.size(), eval::absoluteTrajectoryError(e, t, eval::TrajectoryAlignment::Se3).rmse,
                    eval::absoluteTrajectoryError(o, t, eval::TrajectoryAlignment::Se3).rmse);
    }
    for (std::size_t k = 0; k < r.bundles.size(); ++k) {
      odom.push_back(T * r.bundles[k].odom_pose);
      odom_ref.push_back(host0_inv * r.truth[k]);
    }
  }
  {
    // The host's own trajectory alone, against its own odometry.
    const std::size_t n = opt.trajectory(host).size();
    const std::vector<Pose> e(est.begin(), est.begin() + n), t(ref.begin(), ref.begin() + n);
    const std::size_t m = s.robots[0].bundles.size();
    const std::vector<Pose> o(odom.begin(), odom.begin() + m), ot(odom_ref.begin(), odom_ref.begin() + m);
    out.host_ate_m = eval::absoluteTrajectoryError(e, t, eval::TrajectoryAlignment::Se3).rmse;
    out.host_odom_ate_m = eval::absoluteTrajectoryError(o, ot, eval::TrajectoryAlignment::Se3).rmse;
  }
  const eval::AteResult ate = eval::absoluteTrajectoryError(est, ref, eval::TrajectoryAlignment::Se3);
  out.ate_m = ate.rmse;
  out.odom_ate_m = eval::absoluteTrajectoryError(odom, odom_ref, eval::TrajectoryAlignment::Se3).rmse;

  // Confirmed landmarks against the object most of their detections came from.
  const Pose to_world = s.robots[0].truth.front() * ate.alignment.T;
  std::map<int, std::vector<Object>> of_truth;  // confirmed landmarks (world frame) by true object
  double sq = 0;
  int scored = 0;
  for (const Object& lm : opt.landmarks(true)) {
    ++out.landmarks;
    if (!votes[host].count(lm.id)) continue;
    const int best = majority(votes[host], lm.id);
    if (best < 0) {
      ++out.false_landmarks;
      continue;
    }
    of_truth[best].push_back(transformObject(to_world, lm));
    const double e = horizontalError(of_truth[best].back(), s.landmarks[best]);
    sq += e * e;
    ++scored;
  }
  int extra = 0;
  for (const auto& [i, lms] : of_truth) {
    extra += static_cast<int>(lms.size()) - 1;
    if (lms.size() < 2 || !spdlog::should_log(spdlog::level::debug)) continue;
    std::string t;  // each duplicated object: its landmarks' ids, classes, observations, offsets
    for (const Object& lm : lms)
      t += fmt::format(" [id {} class {} obs {} off {:.2f} m]", lm.id, lm.class_id, lm.num_observations,
                       horizontalError(lm, s.landmarks[i]));
    spdlog::debug("duplicated object {} (class {}):{}", i, s.landmarks[i].class_id, t);
  }
  out.duplicate_fraction = scored ? static_cast<double>(extra) / scored : 0;
  out.landmark_rmse_m = scored ? std::sqrt(sq / scored) : 0;
  return out;
}

}  // namespace slide
