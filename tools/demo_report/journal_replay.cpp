// slide-journal-replay: replays one optimizer's journal (every accepted input of a team run,
// in the order the daemon took them) through the same node in-process, and prints against the
// simulator's ground truth what each loop closure and inter-robot transform did to the
// estimate: the input's own error, then the host's own trajectory (no alignment, in its
// odometry frame) and each merged peer's frame. The evidence behind "which closure broke it".
#include <lcm/lcm-cpp.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "app/app.h"
#include "backend/backend_config.h"
#include "bench/stats.h"
#include "eval/ate.h"
#include "eval/transform_error.h"
#include "objects/class_table.h"
#include "bundle_messages.h"
#include "optimizer_node.h"
#include "slide/keypose_bundle_t.hpp"
#include "slide/loop_closure_t.hpp"
#include "team_truth.h"

using namespace slide;

namespace {

// Ground-truth pose of a robot (world frame) at the stamp nearest t; nullptr beyond 50 ms.
const StampedPose* truthAt(const RobotTruth& r, double t) {
  const auto& g = r.ground_truth;
  auto it = std::lower_bound(g.begin(), g.end(), t, [](const StampedPose& p, double s) { return p.t < s; });
  const StampedPose* best = nullptr;
  if (it != g.end()) best = &*it;
  if (it != g.begin() && (!best || std::abs(std::prev(it)->t - t) < std::abs(best->t - t))) best = &*std::prev(it);
  return best && std::abs(best->t - t) <= 0.05 ? best : nullptr;
}

struct TrajectoryError {
  double rmse = NAN, last = NAN;
  double aligned_rmse = NAN;  // after the best rigid (SE3) alignment to the truth, as the demo report's ATE
  int poses = 0;
};

// A robot's key poses as the host holds them, against truth expressed in the host's frame; with
// `odom_of`, the robot's raw odometry at the same key poses instead (the same measure).
TrajectoryError trajectoryError(const backend::Optimizer& opt, int robot, const TeamTruth& truth,
                                const std::map<std::pair<int, int>, Pose>* odom_of = nullptr) {
  TrajectoryError e;
  const Pose T_host_world = truth.robot(opt.hostRobot()).T_world_odom.inverse();
  double sq = 0;
  std::vector<Pose> est, ref;
  for (const backend::TrajectoryPose& p : opt.trajectory(robot)) {
    const StampedPose* g = truthAt(truth.robot(robot), p.utime * 1e-6);
    if (!g) continue;
    Pose estimate = p.pose;
    if (odom_of) {
      const auto o = odom_of->find({robot, p.seq});
      if (o == odom_of->end()) continue;
      estimate = o->second;
    }
    ref.push_back(T_host_world * g->pose);
    est.push_back(estimate);
    const double d = (estimate.translation() - ref.back().translation()).norm();
    sq += d * d;
    e.last = d;
    ++e.poses;
  }
  if (e.poses) e.rmse = std::sqrt(sq / e.poses);
  if (e.poses >= 3) e.aligned_rmse = eval::absoluteTrajectoryError(est, ref, eval::TrajectoryAlignment::Se3).rmse;
  return e;
}

// The peer's odometry frame as the host's graph holds it (at the peer's first key pose).
std::optional<eval::TransformError> mergedFrameError(const backend::Optimizer& opt, int peer, const TeamTruth& truth,
                                               const std::map<std::pair<int, int>, Pose>& odom_of) {
  const auto traj = opt.trajectory(peer);
  if (traj.empty()) return std::nullopt;
  const auto it = odom_of.find({peer, traj.front().seq});
  if (it == odom_of.end()) return std::nullopt;
  return eval::transformError(traj.front().pose * it->second.inverse(), truth.T_a_b(opt.hostRobot(), peer));
}

void printState(const backend::Optimizer& opt, const TeamTruth& truth,
                const std::map<std::pair<int, int>, Pose>& odom_of, const char* prefix) {
  const TrajectoryError own = trajectoryError(opt, opt.hostRobot(), truth),
                        odom = trajectoryError(opt, opt.hostRobot(), truth, &odom_of);
  std::printf("%s own %d poses rmse %.3f m last %.3f m, SE3-aligned %.3f m (odometry %.3f / %.3f m, aligned %.3f m); "
              "landmarks %d",
              prefix, own.poses, own.rmse, own.last, own.aligned_rmse, odom.rmse, odom.last, odom.aligned_rmse,
              opt.numLandmarks());
  std::printf("; odometry scale %.4f", opt.odometryScale(opt.hostRobot()));
  for (int r : opt.robots()) {
    if (r == opt.hostRobot()) continue;
    const auto e = mergedFrameError(opt, r, truth, odom_of);
    const TrajectoryError te = trajectoryError(opt, r, truth);
    if (e)
      std::printf("; peer %d frame %.2f m / %.2f deg, poses rmse %.2f m, scale %.4f", r, e->translation_m, e->yaw_deg,
                  te.rmse, opt.odometryScale(r));
  }
  std::printf("\n");
}

// Each own observation placed in the world by the true key pose, against the nearest true
// object of its class within 2 m: the offset along the line of sight (positive: beyond the
// object's centre) and across it, per class. Which classes' observations are biased, and by how
// much, independently of the estimate.
class ObservationErrors {
 public:
  explicit ObservationErrors(const ClassTable& classes) : classes_(classes) {}

  void add(const KeyPoseBundle& b, const RobotTruth& truth, const std::vector<Object>& objects) {
    const StampedPose* g = truthAt(truth, b.utime * 1e-6);
    if (!g) return;
    for (const Object& o : b.objects) {
      const Eigen::Vector3d p = g->pose * o.position();
      const Object* best = nullptr;
      double best_d = 2.0;
      for (const Object& t : objects)
        if (t.class_id == o.class_id && (t.position() - p).head<2>().norm() < best_d) {
          best_d = (t.position() - p).head<2>().norm();
          best = &t;
        }
      Errors& e = errors_[o.class_id];
      if (!best) {
        ++e.unmatched;
        continue;
      }
      const Eigen::Vector2d ray = (p - g->pose.translation()).head<2>().normalized();
      const Eigen::Vector2d d = (p - best->position()).head<2>();
      e.along.push_back(d.dot(ray));
      e.range.push_back(o.position().head<2>().norm());
      e.across.push_back(std::abs(ray.x() * d.y() - ray.y() * d.x()));
    }
  }

  void print() const {
    for (const auto& [c, e] : errors_) {
      const ClassInfo* info = classes_.find(c);
      std::printf(
          "observations of %s: %zu within 2 m of a true one (%d not): along the line of sight median %+.3f m "
          "(p10 %+.3f, p90 %+.3f, %+.4f m per metre of range), across median %.3f m\n",
          info ? info->name.c_str() : std::to_string(c).c_str(), e.along.size(), e.unmatched,
          e.along.empty() ? NAN : bench::quantile(e.along, 0.5), e.along.empty() ? NAN : bench::quantile(e.along, 0.1),
          e.along.empty() ? NAN : bench::quantile(e.along, 0.9), bench::slope(e.range, e.along),
          e.across.empty() ? NAN : bench::quantile(e.across, 0.5));
    }
  }

 private:
  struct Errors {
    std::vector<double> along, across, range;  // range: the observation's, for the error's slope over it
    int unmatched = 0;
  };
  const ClassTable& classes_;
  std::map<int, Errors> errors_;
};

struct JournalEvent {
  std::string channel;
  const void* data;
  int datalen;
};

// The optimizer's journal, or the LCM log that was its format before checksums.
std::vector<OptimizerNode::JournalInput> readInputs(const std::string& path) {
  if (team::Journal::looksLikeJournal(path)) {
    team::JournalRecovery rec;
    auto inputs = OptimizerNode::readJournal(path, &rec);
    if (rec.dropped_bytes)
      spdlog::warn("{}: {} damaged bytes after {} good records are not replayed", path, rec.dropped_bytes, rec.records);
    return inputs;
  }
  lcm::LogFile in(path, "r");
  if (!in.good()) throw std::runtime_error(path + ": neither a journal nor an LCM log");
  std::vector<OptimizerNode::JournalInput> inputs;
  while (const lcm::LogEvent* e = in.readNextEvent()) {
    const auto* p = static_cast<const std::uint8_t*>(e->data);
    inputs.push_back({e->channel, std::vector<uint8_t>(p, p + e->datalen)});
  }
  return inputs;
}

}  // namespace

// The host's own bundle b added with each object's association listed: the landmark it joined
// (new or not), that landmark's place before (host frame), and the true objects nearest to the
// object (placed by the true key pose) and to the landmark (placed by the host's true frame).
static void explainBundle(backend::Optimizer& opt, const KeyPoseBundle& b, const TeamTruth& truth, const ClassTable& classes,
                          const std::map<std::pair<int, int>, Pose>& odom_of) {
  std::map<std::int64_t, Object> before;
  for (const Object& o : opt.landmarks(false)) before[o.id] = o;
  // Where odometry from the latest key pose puts this one, before the update.
  Pose T_predicted = Pose::Identity();
  const std::vector<backend::TrajectoryPose> traj_before = opt.trajectory(opt.hostRobot());
  if (!traj_before.empty())
    if (const auto it = odom_of.find({opt.hostRobot(), traj_before.back().seq}); it != odom_of.end())
      T_predicted = traj_before.back().pose * it->second.inverse() * b.odom_pose;
  const backend::UpdateResult r = opt.addBundle(b);
  std::map<std::int64_t, Object> after;
  for (const Object& o : opt.landmarks(false)) after[o.id] = o;
  const RobotTruth& host = truth.robot(opt.hostRobot());
  const StampedPose* g = truthAt(host, b.utime * 1e-6);
  Pose T_odom_body = Pose::Identity();
  for (const backend::TrajectoryPose& p : opt.trajectory(opt.hostRobot()))
    if (p.seq == b.seq) T_odom_body = p.pose;
  auto nearestTruth = [&](const Eigen::Vector3d& w, int class_id, double& d) {
    std::int64_t id = -1;
    d = 1e9;
    for (const Object& t : truth.objects)
      if (classes.sameKind(t.class_id, class_id) && (t.position() - w).head<2>().norm() < d)
        d = (t.position() - w).head<2>().norm(), id = t.id;
    return id;
  };
  // How the update moved the host's earlier key poses (a full solve may move all of them).
  {
    std::map<int, Pose> after_pose;
    for (const backend::TrajectoryPose& p : opt.trajectory(opt.hostRobot())) after_pose[p.seq] = p.pose;
    std::printf("key poses moved by the update (m, every 10th):");
    for (std::size_t i = 0; i < traj_before.size(); i += 10)
      if (const auto it = after_pose.find(traj_before[i].seq); it != after_pose.end())
        std::printf(" %d:%.2f", traj_before[i].seq, (it->second.translation() - traj_before[i].pose.translation()).head<2>().norm());
    std::printf("\n");
  }
  std::printf("bundle %d (%zu objects), %s%s; the key pose lies %.2f m from where odometry put it:\n", b.seq,
              b.objects.size(), r.accepted ? "accepted" : r.reason.c_str(), r.full_solve ? ", full solve" : "",
              (T_odom_body.translation() - T_predicted.translation()).head<2>().norm());
  for (std::size_t k = 0; k < b.objects.size(); ++k) {
    const Object& o = b.objects[k];
    const Eigen::Vector3d in_host = T_odom_body * o.position(), predicted = T_predicted * o.position();
    double d_obj = 0, d_lm = 0;
    const std::int64_t true_obj = g ? nearestTruth(g->pose * o.position(), o.class_id, d_obj) : -1;
    const std::int64_t id = k < r.landmark_ids.size() ? r.landmark_ids[k] : -1;
    const auto was = before.find(id);
    std::printf("  %-6s at (%.2f, %.2f) host", classes.at(o.class_id).name.c_str(), in_host.x(), in_host.y());
    if (const auto* box = std::get_if<Cuboid>(&o.model))
      std::printf(" (box %.1f x %.1f, yaw %.0f deg%s, track %lld)", box->dims.x(), box->dims.y(),
                  std::atan2((T_odom_body.linear() * box->pose.linear())(1, 0), (T_odom_body.linear() * box->pose.linear())(0, 0)) * 180 / M_PI,
                  o.other_reading ? ", two readings" : "", static_cast<long long>(o.id));
    std::printf(": true object %lld at %.2f m; ", static_cast<long long>(true_obj), d_obj);
    if (id < 0) std::printf("dropped\n");
    else if (was == before.end()) std::printf("new landmark %lld\n", static_cast<long long>(id));
    else {
      const std::int64_t true_lm = nearestTruth(host.T_world_odom * was->second.position(), o.class_id, d_lm);
      const Eigen::Vector3d now = after.count(id) ? after.at(id).position() : was->second.position();
      std::printf("landmark %lld, was at (%.2f, %.2f) %.2f m off as odometry put it, now %.2f m off (moved %.2f m); its true "
                  "object %lld at %.2f m%s\n",
                  static_cast<long long>(id), was->second.position().x(), was->second.position().y(),
                  (was->second.position() - predicted).head<2>().norm(), (now - in_host).head<2>().norm(),
                  (now - was->second.position()).head<2>().norm(),
                  static_cast<long long>(true_lm), d_lm,
                  true_lm != true_obj ? "  <-- another object" : "");
    }
  }
}

int main(int argc, char** argv) {
  CLI::App app{"Replay an optimizer journal (state/optimizer<N>.journal of a team run, or the .lcmlog of older runs) "
               "in-process and print, against the simulator's ground truth, what each loop closure and inter-robot transform did to the estimate",
               "slide-journal-replay"};
  app::CommonOptions common;
  app::addCommonOptions(app, common);
  std::string journal, data, config = std::string(SLIDE_SOURCE_DIR) + "/config/backend.yaml",
                            classes_path = std::string(SLIDE_SOURCE_DIR) + "/config/classes.yaml";
  int robot = 0, every = 50;
  std::vector<int> robots{0, 1, 2};
  app.add_option("--journal", journal, "Optimizer journal (or the LCM log of versions before checksums)")->required();
  app.add_option("--data", data, "Simulator output folder of the run (robot<N>/, objects.csv)")->required();
  app.add_option("--robot", robot, "The journal's host robot")->capture_default_str();
  app.add_option("--robots", robots, "Robot ids of the team")->delimiter(',')->capture_default_str();
  app.add_option("--config", config, "Back-end configuration")->capture_default_str();
  app.add_option("--classes", classes_path, "Class table")->capture_default_str();
  app.add_option("--every", every, "Also print the state every this many bundles")->capture_default_str();
  int explain = -1;
  app.add_option("--explain", explain,
                 "List how the host's own bundle of this sequence number was associated: each object's landmark, "
                 "where the landmark stood before, and the true objects both belong to");
  std::vector<double> votes_near;
  app.add_option("--votes-near", votes_near,
                 "List the host's own detections that lie within 1 m of this world point (x y; placed by the true key "
                 "pose): key pose, range, class and the confidence it votes with")
      ->expected(2);
  bool own_only = false, observation_errors = false;
  app.add_flag("--own-only", own_only, "Replay only the host's own inputs (no peer bundles, no inter-robot transforms)");
  std::vector<int> without;
  app.add_option("--without-peer", without,
                 "Leave out this peer's bundles and the transforms to it (repeatable): what merging it did to the host");
  app.add_flag("--observation-errors", observation_errors,
               "Also print, per class, how far the host's own observations lie from their true objects (placed by the "
               "true key poses) along and across the line of sight");
  return app::runApp(app, common, argc, argv, [&] {
    const TeamTruth truth = readTeamTruth(data, robots);
    const ClassTable classes = ClassTable::load(classes_path);
    OptimizerNode node(backend::loadBackendConfig(config), classes, robot, {}, {});
    ObservationErrors obs_errors(classes);
    const std::vector<OptimizerNode::JournalInput> inputs = readInputs(journal);
    std::map<std::pair<int, int>, Pose> odom_of;  // (robot, seq) -> odometry pose of the bundle
    int bundles = 0, index = 0;
    for (const OptimizerNode::JournalInput& in : inputs) {
      const JournalEvent ev{in.channel, in.bytes.data(), static_cast<int>(in.bytes.size())};
      const JournalEvent* e = &ev;
      ++index;
      if (e->channel == "LOOP_CLOSURE") {
        loop_closure_t m;
        if (m.decode(e->data, 0, e->datalen) < 0) throw std::runtime_error(journal + ": undecodable loop closure");
        const Pose T = poseFromXyzYaw(m.x, m.y, m.z, m.yaw);
        if (own_only && m.robot_a != m.robot_b) continue;
        auto left_out = [&](int r) { return r != robot && std::count(without.begin(), without.end(), r) > 0; };
        if (m.robot_a != m.robot_b && (left_out(m.robot_a) || left_out(m.robot_b))) continue;
        std::printf("#%d after %d bundles: ", index, bundles);
        if (m.robot_a == m.robot_b) {
          std::string err = "truth n/a";
          const backend::Optimizer& opt = node.optimizer();
          std::optional<backend::TrajectoryPose> a, b;
          for (const backend::TrajectoryPose& p : opt.trajectory(m.robot_a)) {
            if (p.seq == m.keypose_a) a = p;
            if (p.seq == m.keypose_b) b = p;
          }
          const StampedPose* ga = a ? truthAt(truth.robot(m.robot_a), a->utime * 1e-6) : nullptr;
          const StampedPose* gb = b ? truthAt(truth.robot(m.robot_a), b->utime * 1e-6) : nullptr;
          if (ga && gb) {
            const eval::TransformError te = eval::transformError(T, ga->pose.inverse() * gb->pose);
            char buf[96];
            std::snprintf(buf, sizeof buf, "error %.2f m / %.2f deg", te.translation_m, te.yaw_deg);
            err = buf;
          }
          std::printf("intra %d key poses %d-%d, %d inliers, %s\n", m.robot_a, m.keypose_a, m.keypose_b, m.num_inliers,
                      err.c_str());
        } else {
          const eval::TransformError te = eval::transformError(T, truth.T_a_b(m.robot_a, m.robot_b));
          std::printf("inter %d <- %d, %d inliers, error %.2f m / %.2f deg\n", m.robot_a, m.robot_b, m.num_inliers,
                      te.translation_m, te.yaw_deg);
        }
        node.handle("LOOP_CLOSURE", e->data, e->datalen);
        printState(node.optimizer(), truth, odom_of, "   ->");
      } else if (e->channel == "KEYPOSE_BUNDLE" || (e->channel == "PEER_BUNDLE" && !own_only)) {
        keypose_bundle_t m;
        if (m.decode(e->data, 0, e->datalen) < 0) throw std::runtime_error(journal + ": undecodable bundle");
        const KeyPoseBundle b = msg::fromLcm(m, nullptr);
        if (b.robot != robot && std::count(without.begin(), without.end(), b.robot)) continue;
        odom_of[{b.robot, b.seq}] = b.odom_pose;
        if (observation_errors && b.robot == robot) obs_errors.add(b, truth.robot(robot), truth.objects);
        if (votes_near.size() == 2 && b.robot == robot)
          if (const StampedPose* g = truthAt(truth.robot(robot), b.utime * 1e-6))
            for (const Object& o : b.objects) {
              const Eigen::Vector3d w = g->pose * o.position();
              if ((w.head<2>() - Eigen::Vector2d(votes_near[0], votes_near[1])).norm() > 1.0) continue;
              const Eigen::Vector3d e = o.extent();
              std::printf("key pose %d: %s, confidence %.2f, range %.1f m, extent %.2f x %.2f x %.2f\n", b.seq,
                          classes.at(o.class_id).name.c_str(), o.confidence, o.position().head<2>().norm(), e.x(), e.y(),
                          e.z());
            }
        if (b.robot == robot && b.seq == explain) explainBundle(node.optimizer(), b, truth, classes, odom_of);
        else node.handle(e->channel, e->data, e->datalen);
        if (++bundles % every == 0) {
          char prefix[64];
          std::snprintf(prefix, sizeof prefix, "#%d %d bundles:", index, bundles);
          printState(node.optimizer(), truth, odom_of, prefix);
        }
      }
    }
    node.optimizer().fullSolve();
    printState(node.optimizer(), truth, odom_of, "final (full solve):");
    std::printf("merges undone: %d, rebuilds: %d\n", node.optimizer().unmerged(), node.optimizer().rebuilds());
    if (observation_errors) obs_errors.print();
    return 0;
  });
}
