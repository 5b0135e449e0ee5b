#include "backend/optimizer.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>

#include "backend/data_association.h"
#include "backend/factors.h"
#include "backend/pose_block.h"
#include "backend/solve_worker.h"

namespace slide::backend {

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

PoseSigma sigma6(double t, double r) {
  PoseSigma s;
  s << t, t, t, r, r, r;
  return s;
}

// The anchor prior of a merged peer's first pose (from an inter-robot transform).
PoseSigma peerAnchorSigma(const BackendConfig& c) {
  PoseSigma s = sigma6(c.peer_translation_sigma, c.peer_rotation_sigma);
  s[2] = c.peer_vertical_sigma;
  return s;
}
}  // namespace

Optimizer::Optimizer(BackendConfig config, ClassTable classes, int host_robot)
    : cfg_(config), classes_(std::move(classes)), host_(host_robot), graph_(config.robust_loss_scale) {
  robots_[host_].merged = true;
  for (int id : classes_.ids()) max_association_distance_ = std::max(max_association_distance_, classes_.at(id).association_distance);
  grid_ = LandmarkGrid(std::max(4.0, max_association_distance_));
}

Optimizer::~Optimizer() = default;
Optimizer::Optimizer(Optimizer&&) noexcept = default;
Optimizer& Optimizer::operator=(Optimizer&&) noexcept = default;

Pose Optimizer::poseOf(int var, const FactorGraph::Values* values) const {
  return fromPoseBlock(values ? (*values)[var].data() : graph_.value(var));
}

double Optimizer::odometryScale(int robot) const {
  const auto it = robots_.find(robot);
  return it == robots_.end() || it->second.scale_var < 0 ? 1.0 : *graph_.value(it->second.scale_var);
}

Pose Optimizer::scaledOdometry(int robot, const Pose& odom_a_b) const {
  Pose T = odom_a_b;
  T.translation() *= odometryScale(robot);
  return T;
}

const Optimizer::KeyPose* Optimizer::findKeyPose(int robot, int seq) const {
  const auto it = robots_.find(robot);
  if (it == robots_.end()) return nullptr;
  const auto& list = it->second.keyposes;
  const auto pos = std::lower_bound(list.begin(), list.end(), seq,
                                    [&](int kp, int s) { return keyposes_[kp].seq < s; });
  if (pos == list.end() || keyposes_[*pos].seq != seq) return nullptr;
  return &keyposes_[*pos];
}

std::pair<double, double> Optimizer::positionSigmas(const Object& body) const {
  const double rho = body.position().head<2>().norm();
  return {std::max(cfg_.position_sigma_floor, cfg_.range_sigma), std::max(cfg_.position_sigma_floor, cfg_.bearing_sigma * rho)};
}

double Optimizer::associationSlack(const Object& body) const {
  const auto [sr, st] = positionSigmas(body);
  return cfg_.association_sigmas * std::max(sr, st);
}

Vector6d Optimizer::odometrySigma(const KeyPoseBundle& b, const Pose& relative, bool bridged) const {
  if (cfg_.use_message_sigma && !bridged && (b.odom_sigma.array() > 0).all()) return b.odom_sigma;
  const double d = relative.translation().norm();
  return sigma6(std::max(cfg_.odom_translation_floor, cfg_.odom_translation_per_m * d),
                std::max(cfg_.odom_rotation_floor, cfg_.odom_rotation_per_m * d));
}

UpdateResult Optimizer::addBundle(const KeyPoseBundle& b) {
  const auto t0 = Clock::now();
  UpdateResult r;
  poll(&r);
  // Bounded: peers (any id a message claims) and what is held of each.
  if (!robots_.count(b.robot) && static_cast<int>(robots_.size()) - 1 >= cfg_.max_peers)
    return reject(r, "too many peers: robot " + std::to_string(b.robot) + " would be peer " +
                         std::to_string(robots_.size()) + " (max_peers " + std::to_string(cfg_.max_peers) + ")");
  static const Robot kNewRobot;
  auto known = robots_.find(b.robot);
  const std::string problem = checkBundle(b, known == robots_.end() ? kNewRobot : known->second);
  if (!problem.empty()) return reject(r, problem);
  Robot& robot = robots_[b.robot];
  inputs_.push_back({Input::Kind::Bundle, b});
  if (!robot.merged) {
    if (static_cast<int>(robot.held.size()) >= cfg_.max_held_bundles)
      return reject(r, "peer store full: robot " + std::to_string(b.robot) + " has " +
                           std::to_string(robot.held.size()) + " bundles held (max_held_bundles)");
    (void)usableObjects(b, r);  // its objects' problems are reported now, when they arrive
    robot.held[b.seq] = b;
    r.accepted = r.held = true;
    r.update_ms = msSince(t0);
    return r;
  }
  std::vector<int> touched;
  bool loop = false;
  const int pose_var = insertBundle(b, r, touched, loop);
  r.solve = solveAfterInsert(b.robot, pose_var, touched, loop, r);
  r.accepted = true;
  r.update_ms = msSince(t0);
  return r;
}

int Optimizer::insertBundle(const KeyPoseBundle& b, UpdateResult& r, std::vector<int>& touched, bool& loop) {
  Robot& robot = robots_[b.robot];
  std::vector<Object> objects = usableObjects(b, r);
  Pose T_w_b;
  int prev_var = -1;
  Pose relative = b.relative_odom;
  bool bridged = false;
  if (robot.keyposes.empty()) {
    T_w_b = robot.T_host_robot * b.odom_pose;
  } else {
    const KeyPose& last = keyposes_[robot.keyposes.back()];
    prev_var = last.var;
    if (b.seq != last.seq + 1) {
      relative = last.odom_pose.inverse() * b.odom_pose;
      bridged = true;
      missing_keyposes_ += b.seq - last.seq - 1;
      r.warnings.push_back("gap: robot " + std::to_string(b.robot) + " key poses " + std::to_string(last.seq + 1) + ".." +
                           std::to_string(b.seq - 1) + " missing, bridged with odometry poses");
    }
    if (cfg_.odom_scale_sigma > 0 && robot.scale_var < 0) {
      const double one = 1.0;
      robot.scale_var = graph_.addVariable(BlockKind::Scalar, &one, false);
      graph_.addFactor(scalePriorFactor(cfg_.odom_scale_sigma), {robot.scale_var}, false);
    }
    T_w_b = poseOf(prev_var) * scaledOdometry(b.robot, relative);
  }
  const int var = graph_.addVariable(BlockKind::Pose, toPoseBlock(T_w_b).data(), false);
  OdometryStep step;
  if (prev_var < 0) {
    const PoseSigma s = b.robot == host_ ? sigma6(cfg_.prior_translation_sigma, cfg_.prior_rotation_sigma)
                                         : peerAnchorSigma(cfg_);
    robot.anchor_factor = graph_.addFactor(posePriorFactor(T_w_b, s), {var}, false);
  } else {
    const Vector6d sigma = odometrySigma(b, relative, bridged);
    if (robot.scale_var >= 0) graph_.addFactor(scaledOdometryFactor(relative, sigma), {prev_var, var, robot.scale_var}, false);
    else graph_.addFactor(relativePoseFactor(relative, sigma), {prev_var, var}, false);
    step = {relative.translation().norm(), sigma.head<3>().maxCoeff(), sigma[5]};
  }
  // The odometry's attitude, taken into the host frame, gives the key pose's roll and pitch
  // (robot frames are gravity-aligned and inter-robot transforms turn about z, so this is the
  // IMU's tilt; the transform only matters for frames that are not).
  if (cfg_.gravity_sigma > 0)
    graph_.addFactor(gravityFactor(Eigen::Quaterniond((robot.T_host_robot * b.odom_pose).linear()), cfg_.gravity_sigma),
                     {var}, false);
  OdometryTotals totals;
  if (!robot.keyposes.empty()) (totals = keyposes_[robot.keyposes.back()].totals).add(step);
  keyposes_.push_back({b.robot, b.seq, b.utime, var, b.odom_pose, step, static_cast<int>(robot.keyposes.size()), totals});
  robot.keyposes.push_back(static_cast<int>(keyposes_.size()) - 1);
  if (var >= static_cast<int>(keypose_of_var_.size())) keypose_of_var_.resize(var + 1, -1);
  keypose_of_var_[var] = robot.keyposes.back();
  ++step_;

  for (Object& o : objects) settleReading(o, T_w_b);
  // Association in the host frame against landmarks near each detection.
  std::vector<Detection> world;
  world.reserve(objects.size());
  std::vector<int> near;
  for (const Object& o : objects) {
    const Eigen::Vector2d p = o.position().head<2>();
    const double rho = p.norm();
    const auto [sr, st] = positionSigmas(o);
    // Radial / tangential covariance of the detection, turned into the host frame.
    const Eigen::Vector2d u = rho > 1e-6 ? Eigen::Vector2d(p / rho) : Eigen::Vector2d::UnitX();
    Eigen::Matrix2d R;
    R.col(0) = u;
    R.col(1) = Eigen::Vector2d(-u.y(), u.x());
    const Eigen::Matrix2d yaw = T_w_b.linear().topLeftCorner<2, 2>();
    const Eigen::Matrix2d cov = yaw * R * Eigen::Vector2d(sr * sr, st * st).asDiagonal() * R.transpose() * yaw.transpose();
    world.push_back({transformObject(T_w_b, o), associationSlack(o),
                     cfg_.association_gate > 0 ? cov : Eigen::Matrix2d::Zero(), cfg_.association_gate});
    grid_.near(world.back().object.position(), max_association_distance_ + world.back().slack + 1.0, near);
  }
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  std::vector<Object> candidate_objects;
  candidate_objects.reserve(near.size());
  for (int i : near) candidate_objects.push_back(landmarkObject(landmarks_[i]));
  std::vector<LandmarkCandidate> candidates;
  const int at = static_cast<int>(robot.keyposes.size()) - 1;
  for (std::size_t k = 0; k < near.size(); ++k) {
    const Landmark& lm = landmarks_[near[k]];
    if (lm.alive && !revisitUnsure(lm, driftBetween(lm, nullptr, b.robot, at)))
      candidates.push_back({near[k], &candidate_objects[k]});
  }
  const std::vector<int> match = associateDetections(world, candidates, classes_);

  for (std::size_t i = 0; i < objects.size(); ++i) {
    int index = match[i];
    if (index < 0) {
      index = addLandmark(world[i].object);
    } else {
      if (step_ - landmarks_[index].last_step > cfg_.loop_gap) loop = true;
      const std::map<int, Span> spans = spansOf(landmarks_[index]);
      if (const auto it = spans.find(b.robot); it != spans.end()) tie(b.robot, it->second, {at, at}, landmarks_[index]);
    }
    addObservation(var, T_w_b, objects[i], landmarks_[index]);
    r.landmark_ids[objects[i].id] = landmarks_[index].id;
    touched.push_back(index);
  }
  return var;
}

SolveReport Optimizer::solveAfterInsert(int robot, int pose_var, const std::vector<int>& touched, bool loop,
                                        UpdateResult& r) {
  if (loop) full_pending_ = true;
  const int since_full = step_ - last_full_step_;
  if (!solving() && ((full_pending_ && since_full >= cfg_.min_full_gap) || since_full >= cfg_.full_every)) {
    if (requestFull(cfg_.full_iterations, r)) return r.solve;  // solved here: it replaces the local solve
  }
  std::vector<int> active;
  const auto& kps = robots_[robot].keyposes;
  for (int k = static_cast<int>(kps.size()) - 1; k >= 0 && k >= static_cast<int>(kps.size()) - cfg_.window_poses; --k)
    active.push_back(keyposes_[kps[k]].var);
  for (int i : touched) {
    if (landmarks_[i].observations > cfg_.settled_observations) continue;
    active.push_back(landmarks_[i].var);
    if (landmarks_[i].dims_var >= 0) active.push_back(landmarks_[i].dims_var);
  }
  std::sort(active.begin(), active.end());
  active.erase(std::unique(active.begin(), active.end()), active.end());
  const SolveReport s = graph_.solveLocal(active, cfg_.local_iterations, cfg_.local_function_tolerance);
  afterSolve(touched, false);
  return s;
}

void Optimizer::afterSolve(const std::vector<int>& moved, bool all) {
  if (all) {
    for (std::size_t i = 0; i < landmarks_.size(); ++i)
      if (landmarks_[i].alive) grid_.move(static_cast<int>(i), landmarkObject(landmarks_[i]).position());
  } else {
    for (int i : moved) grid_.move(i, landmarkObject(landmarks_[i]).position());
  }
}

UpdateResult Optimizer::addRobotTransform(int peer, const Pose& T_host_peer) {
  const auto t0 = Clock::now();
  UpdateResult r;
  poll(&r);
  if (peer == host_) return reject(r, "bad transform: robot " + std::to_string(peer) + " is this robot");
  if (!T_host_peer.matrix().allFinite()) return reject(r, "non-finite value: transform to robot " + std::to_string(peer));
  if (!(T_host_peer.translation().norm() <= cfg_.max_robot_offset_m))
    return reject(r, "absurd transform: robot " + std::to_string(peer) + "'s origin is " +
                         std::to_string(T_host_peer.translation().norm()) + " m away (gates.max_robot_offset_m " +
                         std::to_string(cfg_.max_robot_offset_m) + ")");
  if (refused(peer, T_host_peer))
    return reject(r, "refused transform: robot " + std::to_string(peer) +
                         "'s transform is one whose merge was undone (the estimate left the odometry envelope)");
  if (!replaying_ && robots_[peer].merged) {
    // Against the transform it was merged through (refinements stay within the loop closer's
    // consensus tolerance; a jump means the loop closer replaced it).
    const std::optional<Pose> held = robots_[peer].T_host_robot;
    if (held) {
      const Eigen::Vector4d d = xyzYawOf(held->inverse() * T_host_peer);
      const double dt = (T_host_peer.translation() - held->translation()).norm();
      if (dt > cfg_.remerge_translation_m || std::abs(wrapAngle(d[3])) * 180.0 / M_PI > cfg_.remerge_yaw_deg) {
        // Re-merging throws away the alignment the graph holds now: only for a transform under
        // which more of the peer's landmarks meet the host's than meet them now.
        const std::optional<Pose> frame = mergedFrame(peer);
        const int now = frame ? landmarksMet(peer, Pose::Identity()) : 0;
        const int then = frame ? landmarksMet(peer, T_host_peer * frame->inverse()) : 0;
        if (frame && then <= now)
          return reject(r, "contradicted transform held back: robot " + std::to_string(peer) + "'s new transform is " +
                               std::to_string(dt) + " m from the one it was merged through, and " +
                               std::to_string(then) + " of its landmarks would meet the host's through it against " +
                               std::to_string(now) + " now");
        r.warnings.push_back("robot " + std::to_string(peer) + " un-merged and merged again: the new transform is " +
                             std::to_string(dt) + " m from the one it was merged through (" + std::to_string(then) +
                             " of its landmarks meet the host's through it, " + std::to_string(now) + " now)");
        rebuildWithout(peer, T_host_peer);
        ++unmerged_;
        r.full_solve = true;
        guard(r);
        r.accepted = true;
        r.update_ms = msSince(t0);
        return r;
      }
    }
  }
  inputs_.push_back({Input::Kind::Transform, {}, peer, 0, 0, T_host_peer});
  Robot& robot = robots_[peer];
  if (robot.merged && sharedLandmarks(peer) >= cfg_.refine_until_shared) {
    r.accepted = true;  // journalled; the graph already aligns the two robots
    r.update_ms = msSince(t0);
    return r;
  }
  robot.T_host_robot = T_host_peer;
  if (!robot.merged) {
    robot.merged = true;
    merge_order_.push_back(peer);
    for (const auto& [seq, b] : robot.held) {
      UpdateResult part;
      if (!robot.keyposes.empty() && b.utime < keyposes_[robot.keyposes.back()].utime) {
        reject(part, "timestamp out of order: robot " + std::to_string(peer) + " key pose " + std::to_string(seq));
        continue;
      }
      std::vector<int> touched;
      bool loop = false;
      insertBundle(b, part, touched, loop);
      r.warnings.insert(r.warnings.end(), part.warnings.begin(), part.warnings.end());
    }
    robot.held.clear();
  } else if (!robot.keyposes.empty()) {
    // Refinement: the anchor prior of the peer's first pose is replaced, not duplicated.
    const KeyPose& first = keyposes_[robot.keyposes.front()];
    graph_.removeFactor(robot.anchor_factor);
    robot.anchor_factor = graph_.addFactor(
        posePriorFactor(T_host_peer * first.odom_pose, peerAnchorSigma(cfg_)),
        {first.var}, false);
  }
  if (!robot.keyposes.empty()) requestFull(cfg_.loop_iterations, r);
  r.accepted = true;
  r.update_ms = msSince(t0);
  return r;
}

UpdateResult Optimizer::addLoopClosure(int robot, int seq_a, int seq_b, const Pose& T_a_b) {
  const auto t0 = Clock::now();
  UpdateResult r;
  poll(&r);
  if (!T_a_b.matrix().allFinite()) return reject(r, "non-finite value: loop closure of robot " + std::to_string(robot));
  const KeyPose* a = findKeyPose(robot, seq_a);
  const KeyPose* b = findKeyPose(robot, seq_b);
  if (!a || !b || seq_a == seq_b)
    return reject(r, "unknown key pose: loop closure " + std::to_string(seq_a) + "-" + std::to_string(seq_b) +
                         " of robot " + std::to_string(robot) + " names a key pose not in the graph");
  {
    const auto& list = robots_[robot].keyposes;
    auto indexOf = [&](const KeyPose* k) {
      return static_cast<std::size_t>(std::find_if(list.begin(), list.end(), [&](int i) { return &keyposes_[i] == k; }) -
                                      list.begin());
    };
    const bool forward = a->seq < b->seq;
    const EnvelopeCheck c = envelopeOf(robot, indexOf(forward ? a : b), indexOf(forward ? b : a),
                                       forward ? T_a_b : Pose(T_a_b.inverse()));
    if (!c.inside)
      return reject(r, "implausible loop closure: robot " + std::to_string(robot) + " key poses " +
                           std::to_string(seq_a) + "-" + std::to_string(seq_b) + " is " + std::to_string(c.translation_m) +
                           " m / " + std::to_string(c.yaw_deg) + " deg from its odometry (envelope " +
                           std::to_string(c.allowed_m) + " m / " + std::to_string(c.allowed_deg) + " deg)");
  }
  inputs_.push_back({Input::Kind::Loop, {}, robot, seq_a, seq_b, T_a_b});
  // A repeat of a closure still waiting replaces it (one already in the graph is replaced when
  // this one enters).
  pending_loops_.erase(std::remove_if(pending_loops_.begin(), pending_loops_.end(),
                                      [&](const PendingLoop& l) { return l.robot == robot && l.seq_a == seq_a && l.seq_b == seq_b; }),
                       pending_loops_.end());
  pending_loops_.push_back({robot, seq_a, seq_b, T_a_b});
  // A running solve without loop closures of its own (periodic, re-observed landmarks) gives
  // way: the robot is back at a known place now, and every key pose placed before the
  // closure is taken in adds detections far from their landmarks.
  yieldToLoop();
  requestFull(cfg_.loop_iterations, r);
  r.accepted = true;
  r.update_ms = msSince(t0);
  return r;
}

std::vector<Object> Optimizer::landmarks(bool confirmed_only) const {
  std::vector<Object> out;
  for (const Landmark& lm : landmarks_)
    if (lm.alive && (!confirmed_only || lm.observations >= cfg_.min_observations)) out.push_back(landmarkObject(lm));
  return out;
}

namespace {
// Key poses (either end) within which an older tie makes a new one needless.
constexpr int kTieSpacing = 5;
}  // namespace

double Optimizer::driftBetween(int robot, Span x, Span y, double enough) const {
  const Robot& rb = robots_.at(robot);
  // The steps from key pose k to the nearest of a span (none from within it).
  auto to = [&](Span s, int k) {
    const int end = std::clamp(k, s.first, s.second);
    return keyposes_[rb.keyposes[std::max(k, end)]].totals - keyposes_[rb.keyposes[std::min(k, end)]].totals;
  };
  if (!(y.first > x.second || y.second < x.first)) return 0.0;  // seen in turns: no drift between them
  double best = driftRadius(y.first > x.second ? to(y, x.second) : to(y, x.first));
  const PoseSigma loop = loopSigma();
  const OdometryTotals tied{loop[0] * loop[0], loop[5] * loop[5], 0.0};
  for (auto t = rb.ties.begin(); t != rb.ties.end() && best > enough; ++t)
    best = std::min({best, driftRadius(to(x, t->first) + tied + to(y, t->second)),
                     driftRadius(to(x, t->second) + tied + to(y, t->first))});
  return best;
}

std::map<int, Optimizer::Span> Optimizer::spansOf(const Landmark& lm) const {
  std::map<int, Span> out;
  for (const Observation& o : lm.seen) {
    const KeyPose& kp = keyPoseOfVar(o.pose_var);
    const auto [it, added] = out.emplace(kp.robot, Span{kp.index, kp.index});
    if (!added) it->second = {std::min(it->second.first, kp.index), std::max(it->second.second, kp.index)};
  }
  return out;
}

double Optimizer::driftBetween(const Landmark& a, const Landmark* b, int robot, int at) const {
  const ClassInfo* c = classes_.find(a.class_id);
  if (cfg_.revisit_sigmas <= 0 || !c) return -1;  // nothing to decide
  const double enough = c->association_distance / cfg_.revisit_sigmas;  // within it, never drifted apart
  const std::map<int, Span> span_a = spansOf(a);
  const std::map<int, Span> span_b = b ? spansOf(*b) : std::map<int, Span>{{robot, {at, at}}};
  double best = -1;
  for (const auto& [r, x] : span_a) {
    const auto it = span_b.find(r);
    if (it == span_b.end()) continue;
    const double d = driftBetween(r, x, it->second, enough);
    if (best < 0 || d < best) best = d;
    if (best <= enough) break;
  }
  return best;
}

void Optimizer::tie(int robot, Span x, Span y, const Landmark& lm) {
  if (cfg_.revisit_sigmas <= 0 || !(y.first > x.second || y.second < x.first)) return;
  const int i = y.first > x.second ? x.second : x.first, j = y.first > x.second ? y.first : y.second;
  Robot& rb = robots_.at(robot);
  const OdometryTotals along = keyposes_[rb.keyposes[std::max(i, j)]].totals - keyposes_[rb.keyposes[std::min(i, j)]].totals;
  if (!driftedApart(lm, driftRadius(along))) return;
  for (const auto& [a, b] : rb.ties)
    if ((std::abs(a - i) <= kTieSpacing && std::abs(b - j) <= kTieSpacing) ||
        (std::abs(a - j) <= kTieSpacing && std::abs(b - i) <= kTieSpacing))
      return;
  rb.ties.emplace_back(i, j);
}

bool Optimizer::driftedApart(const Landmark& lm, double drift) const {
  if (cfg_.revisit_sigmas <= 0 || drift <= 0) return false;
  const ClassInfo* c = classes_.find(lm.class_id);
  return c && cfg_.revisit_sigmas * drift > c->association_distance;
}

namespace {
// Beyond this drift radius no object is taken as alone (a search too wide to be worth its cost).
constexpr double kMaxAloneRadius = 15.0;
}  // namespace

bool Optimizer::revisitUnsure(const Landmark& lm, double drift, const Landmark* other) const {
  if (!driftedApart(lm, drift)) return false;
  const double radius = cfg_.revisit_sigmas * drift;
  if (radius > kMaxAloneRadius) return true;
  std::vector<int> near;
  const Eigen::Vector3d p = landmarkObject(lm).position();
  grid_.near(p, radius, near);
  for (int i : near) {
    const Landmark& o = landmarks_[i];
    if (&o == &lm || &o == other || !o.alive || !classes_.sameKind(o.class_id, lm.class_id)) continue;
    if ((landmarkObject(o).position() - p).head<2>().norm() <= radius) return true;
  }
  return false;
}

const Optimizer::KeyPose& Optimizer::keyPoseOfVar(int var) const { return keyposes_[keypose_of_var_[var]]; }

// The alive landmarks the host observed and those `peer` observed (one landmark may be in both).
void Optimizer::observedBy(int peer, std::vector<const Landmark*>& host, std::vector<const Landmark*>& other) const {
  for (const Landmark& lm : landmarks_) {
    if (!lm.alive) continue;
    bool by_host = false, by_peer = false;
    for (const Observation& o : lm.seen) {
      const int r = keyPoseOfVar(o.pose_var).robot;
      by_host = by_host || r == host_;
      by_peer = by_peer || r == peer;
    }
    if (by_host) host.push_back(&lm);
    if (by_peer) other.push_back(&lm);
  }
}

int Optimizer::landmarksMet(int peer, const Pose& C) const {
  std::vector<const Landmark*> host, other;
  observedBy(peer, host, other);
  std::vector<Eigen::Vector3d> at(host.size());
  LandmarkGrid grid;  // of the host's landmarks: linear in the map sizes
  for (std::size_t i = 0; i < host.size(); ++i) grid.move(static_cast<int>(i), at[i] = landmarkObject(*host[i]).position());
  int met = 0;
  std::vector<int> near;
  for (const Landmark* lm : other) {
    const Eigen::Vector3d p = C * landmarkObject(*lm).position();
    const double gate = classes_.at(lm->class_id).association_distance;
    near.clear();
    grid.near(p, gate, near);
    met += std::any_of(near.begin(), near.end(), [&](int i) {
      return host[i]->class_id == lm->class_id && (at[i] - p).head<2>().norm() <= gate;
    });
  }
  return met;
}

int Optimizer::sharedLandmarks(int peer) const {
  std::vector<const Landmark*> host, other;
  observedBy(peer, host, other);
  std::sort(host.begin(), host.end());
  int n = 0;
  for (const Landmark* lm : other) n += std::binary_search(host.begin(), host.end(), lm);
  return n;
}

std::vector<Object> Optimizer::ownLandmarks() const {
  std::vector<Object> out;
  for (const Landmark& lm : landmarks_) {
    if (!lm.alive) continue;
    const auto own = std::count_if(lm.seen.begin(), lm.seen.end(),
                                   [&](const Observation& o) { return keyPoseOfVar(o.pose_var).robot == host_; });
    if (own >= cfg_.min_observations) out.push_back(landmarkObject(lm));
  }
  return out;
}

int Optimizer::numLandmarks(bool confirmed_only) const {
  int n = 0;
  for (const Landmark& lm : landmarks_) n += lm.alive && (!confirmed_only || lm.observations >= cfg_.min_observations);
  return n;
}

std::vector<int> Optimizer::robots() const {
  std::vector<int> out;
  for (const auto& [id, r] : robots_)
    if (r.merged) out.push_back(id);
  return out;
}

bool Optimizer::merged(int robot) const {
  const auto it = robots_.find(robot);
  return it != robots_.end() && it->second.merged;
}

int Optimizer::numPeersMerged() const { return static_cast<int>(robots().size()) - 1; }

int Optimizer::numHeld() const {
  int n = 0;
  for (const auto& [id, r] : robots_) n += static_cast<int>(r.held.size());
  return n;
}

std::vector<TrajectoryPose> Optimizer::trajectory(int robot) const {
  std::vector<TrajectoryPose> out;
  const auto it = robots_.find(robot);
  if (it == robots_.end()) return out;
  for (int k : it->second.keyposes) out.push_back({keyposes_[k].seq, keyposes_[k].utime, poseOf(keyposes_[k].var)});
  return out;
}

Optimizer::Batch Optimizer::solveBatch() const {
  Batch b;
  const auto t0 = Clock::now();
  const FactorGraph::Values values = graph_.solveBatch(200, 1e-10, &b.report, cfg_.num_threads);
  b.ms = msSince(t0);
  for (const auto& [id, r] : robots_)
    for (int k : r.keyposes) b.trajectories[id].push_back({keyposes_[k].seq, keyposes_[k].utime, poseOf(keyposes_[k].var, &values)});
  for (const Landmark& lm : landmarks_)
    if (lm.alive && lm.observations >= cfg_.min_observations) b.landmarks.push_back(landmarkObject(lm, &values));
  return b;
}

}  // namespace slide::backend
