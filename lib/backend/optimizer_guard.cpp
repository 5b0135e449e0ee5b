// Soundness of the optimizer's estimate: the odometry envelope of every robot's trajectory
// (about its odometry times the scale the graph estimates for it, when it estimates one),
// un-merging a peer (rebuilding the graph from the recorded inputs without its transform),
// and undoing merges after which some robot's trajectory left its envelope.
#include <cmath>

#include "backend/optimizer.h"
#include "backend/solve_worker.h"

namespace slide::backend {

EnvelopeCheck Optimizer::envelopeOf(int robot, std::size_t i, std::size_t j, const Pose& T_i_j) const {
  const std::vector<int>& list = robots_.at(robot).keyposes;
  std::vector<OdometryStep> steps;
  for (std::size_t k = i + 1; k <= j && k < list.size(); ++k) steps.push_back(keyposes_[list[k]].step);
  const Pose odom = scaledOdometry(
      robot, keyposes_[list[i]].odom_pose.inverse() * keyposes_[list[std::min(j, list.size() - 1)]].odom_pose);
  return checkAgainstOdometry(steps, odom, T_i_j, cfg_.envelope);
}

int Optimizer::robotOutsideEnvelope(std::string* why) const {
  for (const auto& [id, robot] : robots_) {
    if (!robot.merged || robot.keyposes.size() < 2) continue;
    const KeyPose& first = keyposes_[robot.keyposes.front()];
    const Pose est0 = poseOf(first.var);
    OdometryDrift drift;  // of the steps from the first key pose to kp
    for (std::size_t k = 1; k < robot.keyposes.size(); ++k) {
      const KeyPose& kp = keyposes_[robot.keyposes[k]];
      drift.add(kp.step);
      if (k % 5 != 0 && k + 1 != robot.keyposes.size()) continue;  // every fifth and the last
      const EnvelopeCheck c =
          checkAgainstOdometry(drift, scaledOdometry(id, first.odom_pose.inverse() * kp.odom_pose),
                               est0.inverse() * poseOf(kp.var), cfg_.envelope);
      if (!c.inside) {
        if (why)
          *why = "robot " + std::to_string(id) + " key pose " + std::to_string(kp.seq) + " is " +
                 std::to_string(c.translation_m) + " m / " + std::to_string(c.yaw_deg) +
                 " deg from its odometry (envelope " + std::to_string(c.allowed_m) + " m / " +
                 std::to_string(c.allowed_deg) + " deg)";
        return id;
      }
    }
  }
  return -1;
}

std::optional<Pose> Optimizer::mergedFrame(int peer) const {
  const auto it = robots_.find(peer);
  if (it == robots_.end() || !it->second.merged || it->second.keyposes.empty()) return std::nullopt;
  const KeyPose& first = keyposes_[it->second.keyposes.front()];
  return Pose(poseOf(first.var) * first.odom_pose.inverse());
}

bool Optimizer::refused(int peer, const Pose& T) const {
  const auto it = refused_.find(peer);
  if (it == refused_.end()) return false;
  for (const Pose& R : it->second) {
    const double dt = (R.translation() - T.translation()).norm();
    const double dyaw = std::abs(wrapAngle(xyzYawOf(R.inverse() * T)[3])) * 180.0 / M_PI;
    if (dt <= cfg_.remerge_translation_m && dyaw <= cfg_.remerge_yaw_deg) return true;
  }
  return false;
}

void Optimizer::rebuildWithout(int peer, const std::optional<Pose>& T_host_peer) {
  Optimizer fresh(cfg_, classes_, host_);
  fresh.replaying_ = true;
  fresh.refused_ = refused_;
  for (const Input& in : inputs_) {
    switch (in.kind) {
      case Input::Kind::Bundle: fresh.addBundle(in.bundle); break;
      case Input::Kind::Transform:
        if (in.robot != peer) fresh.addRobotTransform(in.robot, in.T);
        break;
      case Input::Kind::Loop: fresh.addLoopClosure(in.robot, in.seq_a, in.seq_b, in.T); break;
    }
  }
  if (T_host_peer) fresh.addRobotTransform(peer, *T_host_peer);
  fresh.replaying_ = false;
  fresh.rejected_ = rejected_;
  fresh.rejections_ = rejections_;
  fresh.merges_ += merges_;
  fresh.detached_ += detached_;
  fresh.unmerged_ = unmerged_;
  fresh.rebuilds_ = rebuilds_ + 1;
  // The worker stays; a solve of the old graph still running is dropped (another epoch).
  cancelSolve();
  fresh.epoch_ = epoch_ + 1;
  std::unique_ptr<SolveWorker> worker = std::move(worker_);
  fresh.solve_hook_ = solve_hook_;
  *this = std::move(fresh);
  worker_ = std::move(worker);
}

void Optimizer::guard(UpdateResult& r) {
  if (!cfg_.guard_estimate || replaying_) return;
  std::string why;
  for (int outside; (outside = robotOutsideEnvelope(&why)) >= 0;) {
    if (merge_order_.empty()) {
      r.warnings.push_back("estimate outside the odometry envelope, no merge left to undo: " + why);
      return;
    }
    // A merged peer that left its own envelope was merged through the transform that bent it;
    // when the host left its envelope, the newest merge is the suspect.
    const int peer = outside != host_ ? outside : merge_order_.back();
    refused_[peer].push_back(robots_[peer].T_host_robot);
    r.warnings.push_back("merge of robot " + std::to_string(peer) + " undone, its transform refused: " + why);
    rebuildWithout(peer, std::nullopt);
    ++unmerged_;
  }
}

}  // namespace slide::backend
