// slide-journal-replay: replays one optimizer's journal (every accepted input of a team run,
// in the order the daemon took them) through the same node in-process, and prints against the
// simulator's ground truth what each loop closure and inter-robot transform did to the
// estimate: the input's own error, then the host's own trajectory (no alignment, in its
// odometry frame) and each merged peer's frame. The evidence behind "which closure broke it".
#include <lcm/lcm-cpp.hpp>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "app/app.h"
#include "backend/backend_config.h"
#include "bench/stats.h"
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
  int poses = 0;
};

// A robot's key poses as the host holds them, against truth expressed in the host's frame; with
// `odom_of`, the robot's raw odometry at the same key poses instead (the same measure).
TrajectoryError trajectoryError(const backend::Optimizer& opt, int robot, const TeamTruth& truth,
                                const std::map<std::pair<int, int>, Pose>* odom_of = nullptr) {
  TrajectoryError e;
  const Pose T_host_world = truth.robot(opt.hostRobot()).T_world_odom.inverse();
  double sq = 0;
  for (const backend::TrajectoryPose& p : opt.trajectory(robot)) {
    const StampedPose* g = truthAt(truth.robot(robot), p.utime * 1e-6);
    if (!g) continue;
    Pose estimate = p.pose;
    if (odom_of) {
      const auto o = odom_of->find({robot, p.seq});
      if (o == odom_of->end()) continue;
      estimate = o->second;
    }
    const double d = (estimate.translation() - (T_host_world * g->pose).translation()).norm();
    sq += d * d;
    e.last = d;
    ++e.poses;
  }
  if (e.poses) e.rmse = std::sqrt(sq / e.poses);
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
  std::printf("%s own %d poses rmse %.3f m last %.3f m (odometry %.3f / %.3f m); landmarks %d", prefix, own.poses,
              own.rmse, own.last, odom.rmse, odom.last, opt.numLandmarks());
  for (int r : opt.robots()) {
    if (r == opt.hostRobot()) continue;
    const auto e = mergedFrameError(opt, r, truth, odom_of);
    const TrajectoryError te = trajectoryError(opt, r, truth);
    if (e) std::printf("; peer %d frame %.2f m / %.2f deg, poses rmse %.2f m", r, e->translation_m, e->yaw_deg, te.rmse);
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
      e.across.push_back(std::abs(ray.x() * d.y() - ray.y() * d.x()));
    }
  }

  void print() const {
    for (const auto& [c, e] : errors_) {
      const ClassInfo* info = classes_.find(c);
      std::printf(
          "observations of %s: %zu within 2 m of a true one (%d not): along the line of sight median %+.3f m "
          "(p10 %+.3f, p90 %+.3f), across median %.3f m\n",
          info ? info->name.c_str() : std::to_string(c).c_str(), e.along.size(), e.unmatched,
          e.along.empty() ? NAN : bench::quantile(e.along, 0.5), e.along.empty() ? NAN : bench::quantile(e.along, 0.1),
          e.along.empty() ? NAN : bench::quantile(e.along, 0.9),
          e.across.empty() ? NAN : bench::quantile(e.across, 0.5));
    }
  }

 private:
  struct Errors {
    std::vector<double> along, across;
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
  bool own_only = false, observation_errors = false;
  app.add_flag("--own-only", own_only, "Replay only the host's own inputs (no peer bundles, no inter-robot transforms)");
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
        odom_of[{b.robot, b.seq}] = b.odom_pose;
        if (observation_errors && b.robot == robot) obs_errors.add(b, truth.robot(robot), truth.objects);
        node.handle(e->channel, e->data, e->datalen);
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
