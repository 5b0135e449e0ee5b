#include "place/loop_closer.h"

#include <algorithm>

namespace slide::place {

namespace {
std::vector<Landmark> subset(const ObjectMap& map, const std::vector<std::size_t>& idx) {
  std::vector<Landmark> all = landmarksOf(map), out;
  std::vector<char> keep(map.size(), 0);
  for (std::size_t i : idx) keep[i] = 1;
  for (const Landmark& l : all)
    if (keep[l.index]) out.push_back(l);
  return out;
}

std::vector<std::size_t> everything(const ObjectMap& map) {
  std::vector<std::size_t> out(map.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = i;
  return out;
}
}  // namespace

bool LoopCloser::setOwnMap(const ObjectMap& map, double now_s) {
  if (map.size() > params_.max_map_objects) {
    ++counts_.oversized_maps;
    return false;
  }
  own_ = map;
  ++own_version_;
  const int seq = keyposes_.empty() ? -1 : keyposes_.back().seq;
  for (const Object& o : own_.objects()) first_seen_.emplace(o.id, seq);
  return true;
}

bool LoopCloser::setPeerMap(int robot, const ObjectMap& map, double now_s) {
  if (robot == params_.robot) return true;
  if (map.size() > params_.max_map_objects) {
    ++counts_.oversized_maps;
    return false;
  }
  auto [it, fresh] = peers_.try_emplace(robot);
  Peer& p = it->second;
  if (fresh) {
    p.filter = ConsensusFilter(params_.consensus);
    // Stagger: robots and peers start their checks at different offsets within the period.
    const int slots = std::max(1, static_cast<int>(params_.inter_period_s / std::max(params_.stagger_s, 1e-3)));
    p.next_due = now_s + params_.stagger_s * ((params_.robot + robot) % slots);
  }
  p.map = map;
  ++p.version;
  return true;
}

void LoopCloser::setTrajectory(std::vector<KeyPose> keyposes) { keyposes_ = std::move(keyposes); }

const KeyPose* LoopCloser::keyPose(int seq) const {
  const auto it = std::lower_bound(keyposes_.begin(), keyposes_.end(), seq,
                                   [](const KeyPose& k, int s) { return k.seq < s; });
  return it != keyposes_.end() && it->seq == seq ? &*it : nullptr;
}

LoopClosure LoopCloser::run(const ObjectMap& a, const std::vector<std::size_t>& ia, const ObjectMap& b,
                            const std::vector<std::size_t>& ib, ConsensusFilter& filter,
                            const std::function<Pose(const Pose&)>& express, bool contest_held) {
  const std::vector<Landmark> la = subset(a, ia), lb = subset(b, ib);
  LoopClosure lc;
  lc.method = params_.method;
  lc.result = recognizePlace(params_.method, la, lb, params_.place);
  if (lc.result.budget_exhausted) ++counts_.budget_exceeded;
  // An ambiguous check's stronger alignment goes to the filter too: it may contest the held
  // transform, or confirm a pending one (consensus_filter.h).
  const bool contest = contest_held && lc.result.ambiguous && feedsAmbiguous(params_.method, filter);
  if (!lc.result.found && !contest) {
    last_reason_ = lc.result.reason;
    return lc;
  }
  for (const LandmarkMatch& m : lc.result.inliers) lc.inliers.emplace_back(a[la[m.a].index].id, b[lb[m.b].index].id);
  const Pose T = express ? express(lc.result.T_a_b) : lc.result.T_a_b;
  const ConsensusFilter::Update u = filter.add(T, static_cast<double>(lc.result.inliers.size()), lc.result.found);
  lc.outcome = u.outcome;
  lc.T_a_b = u.outcome == ConsensusFilter::Outcome::Pending ? T : u.T;
  last_reason_ = lc.result.found ? "" : lc.result.reason;
  return lc;
}

std::optional<LoopClosure> LoopCloser::checkPeer(int robot, Peer& peer) {
  peer.checked_version = peer.version;
  peer.own_checked_version = own_version_;
  if (own_.size() < params_.min_objects || peer.map.size() < params_.min_objects) {
    last_reason_ = "robot " + std::to_string(robot) + ": too few objects (" + std::to_string(own_.size()) + " own, " +
                   std::to_string(peer.map.size()) + " peer)";
    return std::nullopt;
  }
  LoopClosure lc = run(own_, everything(own_), peer.map, everything(peer.map), peer.filter, nullptr, true);
  if (!lc.result.found && lc.outcome == ConsensusFilter::Outcome::Pending) {
    last_reason_ = "robot " + std::to_string(robot) + ": " + last_reason_;
    return std::nullopt;
  }
  lc.robot_a = params_.robot;
  lc.robot_b = robot;
  return lc;
}

std::optional<LoopClosure> LoopCloser::checkIntra() {
  if (keyposes_.empty()) {
    last_reason_ = "intra-robot: no trajectory yet";
    return std::nullopt;
  }
  const KeyPose& cur = keyposes_.back();
  const int old_limit = cur.seq - params_.intra_min_keypose_gap;
  // Path driven from each key pose to the current one (horizontal), for the drift allowance.
  std::vector<double> to_cur(keyposes_.size(), 0.0);
  for (std::size_t i = keyposes_.size() - 1; i-- > 0;)
    to_cur[i] = to_cur[i + 1] + (keyposes_[i + 1].pose.translation() - keyposes_[i].pose.translation()).head<2>().norm();
  const KeyPose* old = nullptr;
  double best = 0, slack = 0;  // the chosen one's distance, and its drift allowance
  for (std::size_t i = 0; i < keyposes_.size() && keyposes_[i].seq <= old_limit; ++i) {
    const double d = (keyposes_[i].pose.translation() - cur.pose.translation()).head<2>().norm();
    const double allowance = params_.intra_drift_fraction * to_cur[i];
    if (d > params_.intra_trigger_radius_m + allowance) continue;
    if (!old || d - allowance <= best - slack) {  // the nearest, relative to what drift allows
      best = d;
      slack = allowance;
      old = &keyposes_[i];
    }
  }
  if (!old) {
    last_reason_ = "intra-robot: no key pose " + std::to_string(params_.intra_min_keypose_gap) + " or more older within " +
                   std::to_string(params_.intra_trigger_radius_m) + " m";
    return std::nullopt;
  }
  std::vector<std::size_t> recent, older;
  for (std::size_t i = 0; i < own_.size(); ++i) {
    const Object& o = own_[i];
    if ((o.position() - cur.pose.translation()).head<2>().norm() > params_.intra_local_radius_m + slack) continue;
    const auto it = first_seen_.find(o.id);
    const int seen = it == first_seen_.end() ? -1 : it->second;
    (seen > old_limit ? recent : older).push_back(i);
  }
  if (recent.size() < params_.min_objects || older.size() < params_.min_objects) {
    last_reason_ = "intra-robot: " + std::to_string(recent.size()) + " recent and " + std::to_string(older.size()) +
                   " old objects near key pose " + std::to_string(cur.seq) + ", too few";
    return std::nullopt;
  }
  const int place = old->seq / std::max(1, params_.intra_min_keypose_gap);
  auto [it, fresh] = intra_places_.try_emplace(place, IntraPlace{ConsensusFilter(params_.consensus), -1, -1, std::nullopt});
  IntraPlace& ip = it->second;
  if (ip.seq_a < 0 || !keyPose(ip.seq_a) || !keyPose(ip.seq_b)) ip.seq_a = old->seq, ip.seq_b = cur.seq;
  // The match M moves the recent objects (placed from the recent key poses) onto the old ones
  // (placed from the old key poses): b's body is at M P_b where a's is at P_a.
  const Pose P_a_inv = keyPose(ip.seq_a)->pose.inverse(), P_b = keyPose(ip.seq_b)->pose;
  LoopClosure lc = run(own_, older, own_, recent, ip.filter, [&](const Pose& M) { return Pose(P_a_inv * M * P_b); });
  if (!lc.result.found) {
    last_reason_ = "intra-robot: " + last_reason_;
    return std::nullopt;
  }
  if (ip.given) {  // fixed once given: confirmed (re-sent as it was) or held back
    if (lc.outcome == ConsensusFilter::Outcome::Refined) {
      lc.T_a_b = *ip.given;
    } else {
      last_reason_ = "intra-robot: a match at the place of key poses " + std::to_string(ip.seq_a) + "-" +
                     std::to_string(ip.seq_b) + " disagrees with the closure it gave";
      lc.outcome = ConsensusFilter::Outcome::Pending;
    }
  } else if (lc.outcome != ConsensusFilter::Outcome::Pending) {
    ip.given = lc.T_a_b;
  }
  lc.robot_a = lc.robot_b = params_.robot;
  lc.keypose_a = ip.seq_a;
  lc.keypose_b = ip.seq_b;
  return lc;
}

std::vector<LoopClosure> LoopCloser::poll(double now_s) {
  std::vector<LoopClosure> out;
  if (now_s >= next_intra_) {
    next_intra_ = now_s + params_.intra_period_s;
    if (auto lc = checkIntra()) out.push_back(std::move(*lc));
  }
  // The most overdue peer whose map (or ours) changed since its last check.
  Peer* due = nullptr;
  int due_robot = -1;
  for (auto& [robot, p] : peers_) {
    const bool changed = p.checked_version != p.version || p.own_checked_version != own_version_;
    if (changed && now_s >= p.next_due && (!due || p.next_due < due->next_due)) {
      due = &p;
      due_robot = robot;
    }
  }
  if (due) {
    due->next_due = now_s + params_.inter_period_s;
    if (auto lc = checkPeer(due_robot, *due)) out.push_back(std::move(*lc));
  }
  return out;
}

}  // namespace slide::place
