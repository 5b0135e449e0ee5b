#include "place/consensus_filter.h"

#include <algorithm>
#include <cmath>

namespace slide::place {

Pose ConsensusFilter::Cluster::mean() const {
  const Eigen::Vector3d t = t_sum / weight;
  return poseFromXyzYaw(t.x(), t.y(), t.z(), std::atan2(sin_sum, cos_sum));
}

int ConsensusFilter::supportOf(int id) const { return static_cast<int>(std::count(recent_.begin(), recent_.end(), id)); }

ConsensusFilter::Update ConsensusFilter::add(const Pose& T, double weight, bool may_establish) {
  if (!may_establish && !params_.ambiguous_may_replace) return {};
  if (!may_establish && held_ < 0 && !params_.ambiguous_may_confirm) return {};
  weight = std::max(weight, 1e-9);
  const Eigen::Vector4d v = xyzYawOf(T);
  // The agreeing cluster nearest in translation, or a new one.
  int id = -1;
  double best = params_.trans_tol;
  for (const auto& [cid, c] : clusters_) {
    const Eigen::Vector4d m = xyzYawOf(c.mean());
    const double dt = (m.head<3>() - v.head<3>()).norm();
    const double dyaw = std::abs(wrapAngle(m[3] - v[3])) * 180.0 / M_PI;
    if (dt <= best && dyaw <= params_.yaw_tol_deg) {
      best = dt;
      id = cid;
    }
  }
  if (!may_establish && held_ < 0) {  // nothing held: only a confirmation of a pending alignment
    if (id < 0 || weight < clusters_.at(id).strongest) return {};
    return confirm(id);
  }
  if (!may_establish && id != held_) {  // a contender: another alignment, stronger than the held one's evidence
    const Cluster& h = clusters_.at(held_);
    const Eigen::Vector4d m = xyzYawOf(h.mean());
    const bool variant = (m.head<3>() - v.head<3>()).norm() <= params_.contest_min_offset &&
                         std::abs(wrapAngle(m[3] - v[3])) * 180.0 / M_PI <= params_.contest_min_yaw_deg;
    if (variant || weight <= h.strongest) return {Outcome::Pending, h.mean(), 0};
  }
  if (id < 0) id = next_id_++;
  // One that agrees with the held transform supports it, but neither moves nor re-sends it.
  const bool support_only = !may_establish && id == held_;
  Cluster& c = clusters_[id];
  if (!support_only) {
    c.t_sum += weight * v.head<3>();
    c.cos_sum += weight * std::cos(v[3]);
    c.sin_sum += weight * std::sin(v[3]);
    c.weight += weight;
    c.strongest = std::max(c.strongest, weight);
  }

  remember(id);
  Update u;
  u.support = supportOf(id);
  if (held_ < 0) {
    if (u.support >= params_.initial_confirmations) {
      held_ = id;
      u.outcome = Outcome::Accepted;
    }
  } else if (id == held_) {
    u.outcome = support_only ? Outcome::Pending : Outcome::Refined;
  } else if (u.support >= params_.change_confirmations && u.support > supportOf(held_)) {
    clusters_.erase(held_);
    held_ = id;
    u.outcome = Outcome::Replaced;
  }
  if (held_ >= 0) u.T = clusters_.at(held_).mean();
  return u;
}

void ConsensusFilter::remember(int id) {
  recent_.push_back(id);
  while (static_cast<int>(recent_.size()) > std::max(1, params_.window)) recent_.pop_front();
  // Forget contenders without recent support (the held cluster always stays).
  for (auto it = clusters_.begin(); it != clusters_.end();)
    it = (it->first != held_ && supportOf(it->first) == 0) ? clusters_.erase(it) : std::next(it);
}

ConsensusFilter::Update ConsensusFilter::confirm(int id) {
  remember(id);  // just recorded: the cluster has support and stays
  Update u;
  u.support = supportOf(id);
  if (u.support >= params_.initial_confirmations) {
    held_ = id;
    u.outcome = Outcome::Accepted;
    u.T = clusters_.at(id).mean();
  }
  return u;
}

std::optional<Pose> ConsensusFilter::held() const {
  if (held_ < 0) return std::nullopt;
  return clusters_.at(held_).mean();
}

bool feedsAmbiguous(PlaceMethod method, const ConsensusFilter& filter) {
  return filter.held() || method == PlaceMethod::SlideGraph;
}

const char* outcomeName(ConsensusFilter::Outcome o) {
  switch (o) {
    case ConsensusFilter::Outcome::Accepted: return "accepted";
    case ConsensusFilter::Outcome::Refined: return "refined";
    case ConsensusFilter::Outcome::Replaced: return "replaced";
    case ConsensusFilter::Outcome::Pending: return "pending";
  }
  return "unknown";
}

}  // namespace slide::place
