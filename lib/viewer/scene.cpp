#include "viewer/scene.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace slide::viewer {

namespace {
// Centimetres for lengths, thousandths for unit vectors and quaternions.
double cm(double v) { return std::round(v * 100.0) / 100.0; }
double milli(double v) { return std::round(v * 1000.0) / 1000.0; }
// A trajectory moved less than this everywhere is not re-sent.
constexpr double kTrajectoryTolerance = 0.02;

std::vector<double> objectRow(const Object& o) {
  std::vector<double> row{static_cast<double>(o.class_id), static_cast<double>(o.shape())};
  auto put = [&row](const Eigen::Vector3d& v, double (*round)(double)) {
    for (int k = 0; k < 3; ++k) row.push_back(round(v[k]));
  };
  std::visit(
      [&](const auto& m) {
        using M = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<M, Cuboid>) {
          put(m.pose.translation(), cm);
          const Eigen::Quaterniond q(m.pose.rotation());
          for (double c : {q.w(), q.x(), q.y(), q.z()}) row.push_back(milli(c));
          put(m.dims, cm);
        } else if constexpr (std::is_same_v<M, Cylinder>) {
          put(m.root, cm);
          put(m.axis, milli);
          row.push_back(cm(m.radius));
          row.push_back(cm(m.length));
        } else {
          put(m.centroid, cm);
          row.push_back(cm(m.radius));
          row.push_back(cm(m.height));
        }
      },
      o.model);
  return row;
}

bool sameTrajectory(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > kTrajectoryTolerance) return false;
  return true;
}

nlohmann::json loopJson(const LoopView& lc) {
  return {{"a", lc.robot_a},      {"b", lc.robot_b},         {"ka", lc.keypose_a},
          {"kb", lc.keypose_b},   {"method", lc.method},     {"x", cm(lc.x)},
          {"y", cm(lc.y)},        {"z", cm(lc.z)},           {"yaw", milli(lc.yaw)},
          {"score", milli(lc.score)}, {"inliers_a", lc.inliers_a}, {"inliers_b", lc.inliers_b}};
}
}  // namespace

Scene::Scene(SceneLimits limits) : limits_(limits) {}

Scene::View& Scene::view(int v) { return views_[v]; }

void Scene::advance(double t) { time_ = std::max(time_, t); }

void Scene::setJson(Versioned<nlohmann::json>& slot, nlohmann::json value) {
  if (slot.version != 0 && slot.value == value) return;
  slot.value = std::move(value);
  slot.version = bump();
}

void Scene::setObjectMap(int v, const std::vector<Object>& objects, double t) {
  advance(t);
  View& w = view(v);
  std::map<std::int64_t, bool> present;
  for (const Object& o : objects) {
    present[o.id] = true;
    std::vector<double> row = objectRow(o);
    auto it = w.objects.find(o.id);
    if (it != w.objects.end() && it->second.row == row) continue;
    w.objects[o.id] = {std::move(row), bump()};
  }
  for (auto it = w.objects.begin(); it != w.objects.end();) {
    if (present.count(it->first)) {
      ++it;
      continue;
    }
    tombstones_.push_back({v, it->first, bump()});
    it = w.objects.erase(it);
  }
  if (tombstones_.size() > limits_.max_tombstones) {
    const std::size_t cut = tombstones_.size() - limits_.max_tombstones / 2;
    tombstone_floor_ = tombstones_[cut - 1].version;
    tombstones_.erase(tombstones_.begin(), tombstones_.begin() + static_cast<long>(cut));
  }
}

void Scene::setTrajectory(int v, int robot, const std::vector<Eigen::Vector3d>& positions, double t) {
  advance(t);
  std::vector<double> flat;
  for (std::size_t i : evenIndices(positions.size(), limits_.max_trajectory_points))
    for (int k = 0; k < 3; ++k) flat.push_back(cm(positions[i][k]));
  auto& slot = view(v).trajectories[robot];
  if (slot.version != 0 && sameTrajectory(slot.value, flat)) return;
  slot.value = std::move(flat);
  slot.version = bump();
}

void Scene::setKeyPose(int v, int seq, const Pose& T, double t) {
  advance(t);
  const Eigen::Vector3d p = T.translation();
  const Eigen::Vector3d x_axis = T.rotation().col(0);
  setJson(view(v).keypose,
          {{"seq", seq}, {"p", {cm(p.x()), cm(p.y()), cm(p.z())}}, {"yaw", milli(std::atan2(x_axis.y(), x_axis.x()))}});
}

void Scene::setInstances(int v, const std::vector<InstanceView>& instances, double t) {
  advance(t);
  nlohmann::json classes = nlohmann::json::array(), counts = nlohmann::json::array(), pts = nlohmann::json::array();
  for (const InstanceView& inst : instances) {
    classes.push_back(inst.class_id);
    counts.push_back(inst.points.size());
    for (const Eigen::Vector3f& p : inst.points)
      for (int k = 0; k < 3; ++k) pts.push_back(cm(p[k]));
  }
  setJson(view(v).instances, {{"c", classes}, {"n", counts}, {"p", pts}});
}

void Scene::addLoopClosure(int v, const LoopView& lc, double t) {
  advance(t);
  View& w = view(v);
  w.loop_list.push_back(lc);
  if (w.loop_list.size() > limits_.max_loops)
    w.loop_list.erase(w.loop_list.begin(), w.loop_list.end() - static_cast<long>(limits_.max_loops));
  nlohmann::json list = nlohmann::json::array();
  for (const LoopView& l : w.loop_list) list.push_back(loopJson(l));
  w.loops.value = std::move(list);
  w.loops.version = bump();
}

void Scene::setOptimizer(int v, const OptimizerView& s, double t) {
  advance(t);
  setJson(view(v).optimizer, {{"keyposes", s.keyposes},
                              {"landmarks", s.landmarks},
                              {"peers", s.peers_merged},
                              {"ms", std::round(s.update_ms * 10.0) / 10.0},
                              {"full", s.full_solve},
                              {"rejected", s.rejected},
                              {"dropped", s.dropped},
                              {"t", std::round(t * 10.0) / 10.0}});
}

void Scene::setSensor(int v, const SensorView& s, double t) {
  advance(t);
  setJson(view(v).sensor, {{"state", s.state},
                           {"sent", s.frames_sent},
                           {"total", s.frames_total},
                           {"source", s.source},
                           {"detections", s.detections},
                           {"reason", s.reason}});
}

void Scene::noteTeamMessage(int listener, int sender, std::size_t bytes, double t) {
  advance(t);
  Listener& l = listeners_[listener];
  if (sender >= 0) l.last_heard[sender] = t;
  l.traffic.emplace_back(t, bytes);
  updateListener(listener, l);
}

void Scene::updateListener(int id, Listener& l) {
  const double from = time_ - limits_.rate_window_s;
  l.traffic.erase(l.traffic.begin(), std::find_if(l.traffic.begin(), l.traffic.end(),
                                                  [from](const auto& e) { return e.first >= from; }));
  std::size_t bytes = 0;
  for (const auto& e : l.traffic) bytes += e.second;
  nlohmann::json linked = nlohmann::json::array();
  for (const auto& [sender, heard] : l.last_heard)
    if (time_ - heard <= limits_.link_timeout_s && sender != id) linked.push_back(sender);
  const double rate = std::round(static_cast<double>(bytes) / limits_.rate_window_s / 10.0) * 10.0;
  setJson(l.summary, {{"linked", linked}, {"bytes_per_s", rate}});
}

void Scene::tick(double t) {
  advance(t);
  for (auto& [id, l] : listeners_) updateListener(id, l);
}

void Scene::reset() {
  views_.clear();
  listeners_.clear();
  tombstones_.clear();
  tombstone_floor_ = 0;
  time_ = 0;
  ++epoch_;
  bump();
}

std::size_t Scene::objectCount(int v) const {
  auto it = views_.find(v);
  return it == views_.end() ? 0 : it->second.objects.size();
}

nlohmann::json Scene::delta(std::uint64_t epoch, std::uint64_t since) const {
  const bool full = epoch != epoch_ || since < tombstone_floor_;
  if (full) since = 0;
  nlohmann::json out = {{"epoch", epoch_}, {"version", version_}, {"reset", full}, {"time", time_}};
  nlohmann::json views = nlohmann::json::object();
  auto putJson = [since](nlohmann::json& into, const char* key, const Versioned<nlohmann::json>& slot) {
    if (slot.version > since) into[key] = slot.value;
  };
  for (const auto& [id, w] : views_) {
    nlohmann::json v = nlohmann::json::object();
    nlohmann::json set = nlohmann::json::array(), del = nlohmann::json::array();
    for (const auto& [oid, e] : w.objects) {
      if (e.version <= since) continue;
      nlohmann::json row = nlohmann::json::array({oid});
      for (double x : e.row) row.push_back(x);
      set.push_back(std::move(row));
    }
    if (!full)
      for (const Tombstone& tomb : tombstones_)
        if (tomb.view == id && tomb.version > since) del.push_back(tomb.id);
    if (!set.empty() || !del.empty()) v["objects"] = {{"set", set}, {"del", del}};
    nlohmann::json traj = nlohmann::json::object();
    for (const auto& [robot, slot] : w.trajectories)
      if (slot.version > since) traj[std::to_string(robot)] = slot.value;
    if (!traj.empty()) v["trajectories"] = traj;
    putJson(v, "keypose", w.keypose);
    putJson(v, "instances", w.instances);
    putJson(v, "optimizer", w.optimizer);
    putJson(v, "sensor", w.sensor);
    putJson(v, "loops", w.loops);
    if (full || !v.empty()) views[std::to_string(id)] = std::move(v);
  }
  out["views"] = std::move(views);
  nlohmann::json team = nlohmann::json::object();
  for (const auto& [id, l] : listeners_)
    if (l.summary.version > since) team[std::to_string(id)] = l.summary.value;
  out["team"] = std::move(team);
  return out;
}

std::vector<std::size_t> evenIndices(std::size_t n, std::size_t keep) {
  std::vector<std::size_t> idx;
  if (n == 0 || keep == 0) return idx;
  if (n <= keep) {
    for (std::size_t i = 0; i < n; ++i) idx.push_back(i);
    return idx;
  }
  for (std::size_t k = 0; k < keep; ++k) idx.push_back(k * (n - 1) / (keep - 1 ? keep - 1 : 1));
  idx.erase(std::unique(idx.begin(), idx.end()), idx.end());
  return idx;
}

}  // namespace slide::viewer
