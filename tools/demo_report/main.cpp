// slide-demo-report: turns a team run (robot-bus and team-bus LCM logs) plus the simulator's
// ground truth into figures, pictures and a Markdown report.
#include <spdlog/spdlog.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <sstream>

#include "app/app.h"
#include "backend/backend_config.h"
#include "bench/report.h"
#include "bench/stats.h"
#include "eval/ate.h"
#include "eval/bandwidth.h"
#include "eval/map_agreement.h"
#include "eval/object_matching.h"
#include "eval/time_association.h"
#include "eval/transform_error.h"
#include "frontend/frontend_config.h"
#include "objects/class_table.h"
#include "plot/map_plot.h"
#include "own_map.h"
#include "run_log.h"
#include "team_truth.h"

using namespace slide;
namespace fs = std::filesystem;

namespace {

struct Options {
  std::string run_dir, data_dir, out_dir, json, classes = std::string(SLIDE_SOURCE_DIR) + "/config/classes.yaml";
  std::vector<int> robots{0, 1, 2};
  double wall_s = NAN;
  std::string perception;  // what the run was started with (demo --perception)
  std::string backend_config = std::string(SLIDE_SOURCE_DIR) + "/config/backend.yaml";
  double match_threshold = 1.0;
  double visible_range = 10.0;
};

struct RobotFigures {
  int robot = 0;
  double ate = NAN, odom_ate = NAN, ate_anchored = NAN, odom_ate_anchored = NAN;
  std::size_t poses = 0, landmarks = 0, trajectories = 0;
  eval::ObjectMappingScore objects;
  std::vector<std::pair<int, eval::TransformError>> closures;  // per peer found (place recognition)
  // What the optimizer made of each merged peer: its estimate of the peer's odometry frame
  // (at the peer's first key pose it holds) and the RMS position error of the peer's key poses
  // in this robot's frame, with no alignment.
  std::vector<std::pair<int, eval::TransformError>> merged;
  std::map<int, Pose> merged_frames;  // the optimizer's T_a_b per merged peer
  std::vector<std::pair<int, double>> peer_traj_rmse;
  double update_ms_median = NAN, update_ms_p99 = NAN;
  int keypose_bundles = 0, peer_bundles = 0;
  // Landmarks per estimated class: {all, at a real object of that class, at a real object of
  // another class only, a second landmark of a real object of its class that another landmark
  // took, at no real object} (one-to-one matching, as for precision).
  std::map<int, std::array<int, 5>> landmark_classes;
  int second_landmarks = 0;
  // Per true class: recall over the real objects near the paths, precision of the landmarks
  // that claim the class against every real object (as the overall figures).
  std::map<int, eval::ClassScore> class_recall, class_precision;
};

// Ground-truth objects within `range` (horizontally) of any robot's true path: what the team
// could have seen.
std::vector<Object> visibleObjects(const TeamTruth& truth, double range) {
  std::vector<Object> out;
  for (const Object& o : truth.objects) {
    bool seen = false;
    for (const RobotTruth& r : truth.robots) {
      for (const StampedPose& p : r.ground_truth)
        if ((p.pose.translation() - o.position()).head<2>().norm() <= range) {
          seen = true;
          break;
        }
      if (seen) break;
    }
    if (seen) out.push_back(o);
  }
  return out;
}

std::vector<StampedPose> stamped(const LoggedTrajectory& t) {
  std::vector<StampedPose> out;
  for (std::size_t i = 0; i < t.t.size(); ++i) out.push_back({t.t[i], t.poses[i]});
  return out;
}

std::vector<Eigen::Vector3d> positions(const std::vector<StampedPose>& traj, const Pose& T = Pose::Identity()) {
  std::vector<Eigen::Vector3d> out;
  for (const StampedPose& p : traj) out.push_back(T * p.pose.translation());
  return out;
}

RobotFigures evaluateRobot(int a, const RobotRunLog& log, const TeamTruth& truth, const std::vector<Object>& visible,
                           const Options& opts) {
  RobotFigures f;
  f.robot = a;
  f.landmarks = log.map.size();
  f.trajectories = log.trajectories.size();
  f.keypose_bundles = log.keypose_bundles;
  f.peer_bundles = log.peer_bundles;
  const RobotTruth& rt = truth.robot(a);
  if (auto it = log.trajectories.find(a); it != log.trajectories.end() && it->second.poses.size() >= 3) {
    const eval::AssociatedPoses est = eval::associatePoses(stamped(it->second), rt.ground_truth, 0.05, 0.0, 3);
    f.poses = est.est.size();
    f.ate = eval::absoluteTrajectoryError(est.est, est.ref, eval::TrajectoryAlignment::Se3).rmse;
    // Without alignment, through the true start: the error a peer inherits when it places this
    // robot's map by a transform between the two odometry frames.
    std::vector<Pose> in_world;
    for (const Pose& p : est.est) in_world.push_back(rt.T_world_odom * p);
    f.ate_anchored = eval::absoluteTrajectoryError(in_world, est.ref, eval::TrajectoryAlignment::None).rmse;
    // Raw odometry at the same instants, as the baseline.
    std::vector<double> key_t(est.t.begin(), est.t.end());
    std::vector<StampedPose> odom_at;
    const eval::AssociatedPoses od = eval::associatePoses(rt.odometry, rt.ground_truth, 0.05, 0.0, 3);
    std::vector<Pose> oe, orf;
    for (std::size_t i = 0; i < od.t.size(); ++i)
      for (double t : key_t)
        if (std::abs(od.t[i] - t) < 1e-6) {
          oe.push_back(od.est[i]);
          orf.push_back(od.ref[i]);
        }
    if (oe.size() >= 3) {
      f.odom_ate = eval::absoluteTrajectoryError(oe, orf, eval::TrajectoryAlignment::Se3).rmse;
      for (Pose& p : oe) p = rt.T_world_odom * p;  // the same anchoring as the estimate's
      f.odom_ate_anchored = eval::absoluteTrajectoryError(oe, orf, eval::TrajectoryAlignment::None).rmse;
    }
  }
  std::vector<Object> in_world;
  for (const Object& o : log.map) in_world.push_back(transformObject(rt.T_world_odom, o));
  eval::ObjectMatchOptions mo;
  mo.threshold = opts.match_threshold;
  mo.planar = true;
  // Recall: of the objects near some robot's path; precision: against every real object, so
  // that a correctly mapped tree farther out is not counted as false.
  f.objects = eval::scoreObjectMap(in_world, visible, mo);
  const eval::ObjectMappingScore against_all = eval::scoreObjectMap(in_world, truth.objects, mo);
  f.objects.overall.precision = against_all.overall.precision;
  for (const eval::ClassScore& c : f.objects.per_class) f.class_recall[c.class_id] = c;
  for (const eval::ClassScore& c : against_all.per_class) f.class_precision[c.class_id] = c;
  eval::ObjectMatchOptions any = mo;
  any.match_classes = false;
  const eval::ObjectMappingScore against_any = eval::scoreObjectMap(in_world, truth.objects, any);
  std::vector<char> right(in_world.size(), 0), somewhere(in_world.size(), 0);
  for (const eval::ObjectMatch& m : against_all.matches) right[m.est] = 1;
  for (const eval::ObjectMatch& m : against_any.matches) somewhere[m.est] = 1;
  const std::vector<char> second = eval::secondEstimates(in_world, truth.objects, against_all, mo);
  for (std::size_t i = 0; i < in_world.size(); ++i) {
    auto& c = f.landmark_classes[in_world[i].class_id];
    ++c[0];
    const bool twice = !somewhere[i] && second[i];
    f.second_landmarks += twice;
    ++c[right[i] ? 1 : somewhere[i] ? 2 : twice ? 3 : 4];
    if (!right[i]) {
      const Eigen::Vector3d x = in_world[i].position(), e = in_world[i].extent();
      spdlog::debug("robot {} landmark {} (class {}, {} observations, extent {:.2f} {:.2f} {:.2f}) at world ({:.1f}, {:.1f}): {}",
                    a, in_world[i].id, in_world[i].class_id, in_world[i].num_observations, e.x(), e.y(), e.z(), x.x(),
                    x.y(),
                    somewhere[i] ? "at a real object of another class"
                    : twice      ? "a second landmark of a real object another landmark took"
                                 : "no real object within the match distance");
    }
  }
  std::vector<char> found(visible.size(), 0);
  for (const eval::ObjectMatch& m : f.objects.matches) found[m.gt] = 1;
  for (std::size_t i = 0; i < visible.size(); ++i)
    if (!found[i]) {
      const Eigen::Vector3d x = visible[i].position();
      spdlog::debug("robot {} missed real object {} (class {}) at world ({:.1f}, {:.1f})", a, visible[i].id,
                    visible[i].class_id, x.x(), x.y());
    }
  const double p = f.objects.overall.precision, r = f.objects.overall.recall;
  f.objects.overall.f1 = p + r > 0 ? 2 * p * r / (p + r) : 0.0;
  for (const auto& [b, c] : log.closures) {
    f.closures.emplace_back(b, eval::transformError(c.T_a_b, truth.T_a_b(a, b)));
    const Eigen::Vector3d d = c.T_a_b.translation() - truth.T_a_b(a, b).translation();
    spdlog::info("robot {} <- {}: place recognition off by x {:.2f} y {:.2f} z {:.2f} m", a, b, d.x(), d.y(), d.z());
  }
  for (const auto& [b, traj] : log.trajectories) {
    if (b == a || traj.frame_robot != a || traj.poses.size() < 3) continue;
    const RobotTruth& peer = truth.robot(b);
    eval::AssociatedPoses in_odom, in_world;
    try {
      in_odom = eval::associatePoses(stamped(traj), peer.odometry, 0.05, 0.0, 3);
      in_world = eval::associatePoses(stamped(traj), peer.ground_truth, 0.05, 0.0, 3);
    } catch (const std::invalid_argument& e) {
      spdlog::warn("robot {}'s trajectory of robot {}: {}", a, b, e.what());
      continue;
    }
    // T_a_b as the optimizer holds it: the peer's first key pose in this robot's frame, composed
    // with the inverse of where the peer's own odometry put that key pose.
    const Pose T_a_b = in_odom.est.front() * in_odom.ref.front().inverse();
    f.merged.emplace_back(b, eval::transformError(T_a_b, truth.T_a_b(a, b)));
    f.merged_frames[b] = T_a_b;
    double sq = 0;
    for (std::size_t i = 0; i < in_world.est.size(); ++i)
      sq += (rt.T_world_odom * in_world.est[i].translation() - in_world.ref[i].translation()).squaredNorm();
    f.peer_traj_rmse.emplace_back(b, std::sqrt(sq / static_cast<double>(in_world.est.size())));
  }
  if (!log.update_ms.empty()) {
    f.update_ms_median = bench::median(log.update_ms);
    f.update_ms_p99 = bench::quantile(log.update_ms, 0.99);
  }
  return f;
}

// The paper-comparable inter-robot figures of one ordered pair (a hosts, b is the peer): the
// transforms are judged against the best rigid alignment of the two robots' own maps (own_map.h)
// over the landmarks both hold, not against the true frames; and the merged map's consistency,
// the distance between the two robots' own landmarks of one real object once b's are placed in
// a's frame by a's merged estimate of b.
struct MapAgreement {
  int a = 0, b = 0;
  std::size_t shared = 0;
  std::optional<eval::HorizontalError> place_vs_maps, merged_vs_maps;
  std::vector<double> merged_distances;
};

MapAgreement mapAgreement(int a, int b, const std::vector<Object>& own_a, const std::vector<Object>& own_b,
                          const RobotRunLog& log_a, const RobotFigures& f, const TeamTruth& truth,
                          const eval::ObjectMatchOptions& mo) {
  MapAgreement out{a, b, 0, std::nullopt, std::nullopt, {}};
  const eval::SharedLandmarks sh =
      eval::sharedLandmarks(own_a, truth.robot(a).T_world_odom, own_b, truth.robot(b).T_world_odom, truth.objects, mo);
  out.shared = sh.in_a.size();
  const std::optional<Pose> T_maps = eval::mapAlignment(sh);  // b's map into a's frame
  if (!T_maps) return out;
  if (const auto it = log_a.closures.find(b); it != log_a.closures.end())
    out.place_vs_maps = eval::horizontalError(it->second.T_a_b, *T_maps);
  if (const auto it = f.merged_frames.find(b); it != f.merged_frames.end()) {
    out.merged_vs_maps = eval::horizontalError(it->second, *T_maps);
    out.merged_distances = eval::landmarkDistances(sh, it->second);
  }
  return out;
}

void plotRobot(int a, const RobotRunLog& log, const TeamTruth& truth, const std::vector<Object>& visible,
               const ClassTable& classes, const std::string& out_base, plot::View view) {
  const Pose T_w_a = truth.robot(a).T_world_odom;
  std::vector<plot::PlotMap> maps;
  maps.push_back({"ground truth", visible, -1, true});
  plot::PlotMap own{"robot" + std::to_string(a) + " merged map", {}, a, false};
  for (const Object& o : log.map) own.objects.push_back(transformObject(T_w_a, o));
  maps.push_back(own);
  std::vector<plot::PlotTrajectory> trajs;
  for (const RobotTruth& r : truth.robots)
    trajs.push_back({"robot" + std::to_string(r.robot) + " truth", positions(r.ground_truth), r.robot, true, {}});
  for (const auto& [b, t] : log.trajectories)
    trajs.push_back({"robot" + std::to_string(b) + " estimate", positions(stamped(t), T_w_a), b, false, {}});
  plot::MapPlotOptions po;
  po.view = view;
  po.title = "robot" + std::to_string(a) + ": merged map and all trajectories";
  po.subtitle = "world frame via robot" + std::to_string(a) + "'s true start; dashed black = ground truth";
  const plot::Canvas c = plot::plotMap(maps, trajs, classes, po);
  c.write(out_base + ".png");
  c.write(out_base + ".svg");
}

std::string num(double v, int prec = 3) {
  if (!std::isfinite(v)) return "n/a";
  std::ostringstream s;
  s << std::fixed << std::setprecision(prec) << v;
  return s.str();
}

// What range of the scene reached the robots' maps, from the run's front-end configuration.
std::string frontEndRange(const std::string& path) {
  if (!std::filesystem::exists(path)) return "Front end: no " + path + " (range not stated).";
  try {
    const frontend::FrontendConfig c = frontend::loadFrontendConfig(path);
    std::ostringstream s;
    s << "Front end (`" << path << "`): the segmenters took returns up to " << num(c.geometric.max_range, 0)
      << " m off (label-free), " << num(c.labelled.max_range, 0) << " m (labelled); key-pose bundles carried ";
    if (c.tracker.report_max_range <= 0 && c.tracker.report_max_range_by_class.empty()) {
      s << "every tracked object.";
    } else {
      s << "objects within " << (c.tracker.report_max_range > 0 ? num(c.tracker.report_max_range, 0) + " m" : "any range");
      for (const auto& [name, r] : c.tracker.report_max_range_by_class) s << " (" << name << ": " << num(r, 0) << " m)";
      s << " of the robot; farther ones were tracked, their class votes counted, but not mapped.";
    }
    return s.str();
  } catch (const std::exception& e) {
    return std::string("Front end: ") + e.what();
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Evaluate a team run: inter-robot transform errors, ATE, object precision/recall, bandwidth; "
               "writes report.md, report.json and pictures",
               "slide-demo-report"};
  Options opts;
  app::CommonOptions common;
  app::addCommonOptions(app, common);
  app.add_option("--run", opts.run_dir, "Run folder with logs/robot<N>.lcmlog (robot bus) and logs/team<N>.lcmlog (team bus on robot N's host)")->required();
  app.add_option("--data", opts.data_dir, "Simulator output folder (robot<N>/, objects.csv)")->required();
  app.add_option("--out", opts.out_dir, "Report folder (default RUN/report)");
  app.add_option("--robots", opts.robots, "Robot ids")->delimiter(',')->capture_default_str();
  app.add_option("--wall-s", opts.wall_s, "Wall time of the run, seconds (reported as demo.wall_s)");
  app.add_option("--perception", opts.perception,
                 "Perception mode the run was started with (label-free, emulated, oracle), stated in the report");
  app.add_option("--json", opts.json, "Write the figures as benchmark JSON (suite system)");
  app.add_option("--classes", opts.classes, "Class table")->capture_default_str();
  app.add_option("--backend-config", opts.backend_config,
                 "Back-end configuration for replaying each robot's own observations (its own map)")
      ->capture_default_str();
  app.add_option("--match-threshold", opts.match_threshold, "Object match distance, metres")->capture_default_str();
  app.add_option("--visible-range", opts.visible_range,
                 "Ground-truth objects within this horizontal distance of a path count as observable")
      ->capture_default_str();
  return app::runApp(app, common, argc, argv, [&] {
    if (opts.out_dir.empty()) opts.out_dir = opts.run_dir + "/report";
    fs::create_directories(opts.out_dir);
    const ClassTable classes = ClassTable::load(opts.classes);
    const TeamTruth truth = readTeamTruth(opts.data_dir, opts.robots);
    const std::vector<Object> visible = visibleObjects(truth, opts.visible_range);

    std::vector<RobotFigures> figs;
    std::map<int, RobotRunLog> logs;
    std::map<int, std::string> detections;  // per robot, from its driver's SENSOR_STATUS
    for (int a : opts.robots) {
      const std::string path = opts.run_dir + "/logs/robot" + std::to_string(a) + ".lcmlog";
      int bad = 0;
      const RobotRunLog& log = logs[a] = readRobotLog(path, a, bad);
      if (bad) spdlog::warn("{}: {} messages failed to decode", path, bad);
      detections[a] = log.detections.empty() ? "unknown (no SENSOR_STATUS logged)" : log.detections;
      figs.push_back(evaluateRobot(a, log, truth, visible, opts));
      const std::string base = opts.out_dir + "/robot" + std::to_string(a);
      plotRobot(a, log, truth, visible, classes, base + "_top", plot::View::top());
      plotRobot(a, log, truth, visible, classes, base + "_oblique", plot::View::oblique());
    }

    TeamTraffic traffic;
    for (int a : opts.robots) {
      const std::string team_log = opts.run_dir + "/logs/team" + std::to_string(a) + ".lcmlog";
      if (!fs::exists(team_log)) {
        spdlog::warn("{}: missing, robot {}'s team traffic is not counted", team_log, a);
        continue;
      }
      const TeamTraffic t = readTeamTraffic(team_log, a);
      if (t.undecodable) spdlog::warn("{}: {} team messages failed to decode", team_log, t.undecodable);
      traffic += t;
    }
    const std::int64_t team_bytes = traffic.bytes();
    double metres = 0;
    for (const RobotTruth& r : truth.robots) metres += r.path_length_m;
    std::size_t max_landmarks = 0;
    for (const RobotFigures& f : figs) max_landmarks = std::max(max_landmarks, f.landmarks);
    const eval::BandwidthFigures bw = eval::bandwidthFigures(double(team_bytes), max_landmarks, metres);

    std::vector<double> trans_err, yaw_err, ates, odom_ates, f1s, precisions, recalls, second_shares;
    std::vector<double> merged_trans_err, merged_yaw_err, peer_rmse, anchored_ates, odom_anchored_ates;
    std::size_t pairs_found = 0;
    for (const RobotFigures& f : figs) {
      for (const auto& [b, e] : f.merged) {
        merged_trans_err.push_back(e.translation_m);
        merged_yaw_err.push_back(e.yaw_deg);
      }
      for (const auto& [b, r] : f.peer_traj_rmse) peer_rmse.push_back(r);
      for (const auto& [b, e] : f.closures) {
        trans_err.push_back(e.translation_m);
        yaw_err.push_back(e.yaw_deg);
        ++pairs_found;
      }
      if (std::isfinite(f.ate)) ates.push_back(f.ate);
      if (std::isfinite(f.ate_anchored)) anchored_ates.push_back(f.ate_anchored);
      if (std::isfinite(f.odom_ate_anchored)) odom_anchored_ates.push_back(f.odom_ate_anchored);
      if (std::isfinite(f.odom_ate)) odom_ates.push_back(f.odom_ate);
      f1s.push_back(f.objects.overall.f1);
      if (f.landmarks > 0) second_shares.push_back(double(f.second_landmarks) / f.landmarks);
      precisions.push_back(f.objects.overall.precision);
      recalls.push_back(f.objects.overall.recall);
    }
    const std::size_t pairs_possible = opts.robots.size() * (opts.robots.size() - 1);
    eval::ObjectMatchOptions mo;
    mo.threshold = opts.match_threshold;
    mo.planar = true;
    std::map<int, std::vector<Object>> own_maps;
    const backend::BackendConfig backend = backend::loadBackendConfig(opts.backend_config);
    for (int a : opts.robots) {
      const std::string journal = opts.run_dir + "/state/optimizer" + std::to_string(a) + ".journal";
      if (!fs::exists(journal)) {
        spdlog::warn("{}: missing, robot {}'s own map is unknown (no map-alignment figures for its pairs)", journal, a);
        continue;
      }
      own_maps[a] = ownOnlyMap(journal, a, backend, classes);
      spdlog::info("robot {}: own map of {} landmarks from {}", a, own_maps[a].size(), journal);
    }
    std::vector<MapAgreement> agreements;
    std::vector<double> place_vs_maps_t, place_vs_maps_yaw, merged_vs_maps_t, consistency;
    for (const RobotFigures& f : figs)
      for (int b : opts.robots) {
        if (b == f.robot || !own_maps.count(f.robot) || !own_maps.count(b)) continue;
        const MapAgreement& g = agreements.emplace_back(
            mapAgreement(f.robot, b, own_maps[f.robot], own_maps[b], logs[f.robot], f, truth, mo));
        if (g.place_vs_maps) {
          place_vs_maps_t.push_back(g.place_vs_maps->translation_m);
          place_vs_maps_yaw.push_back(g.place_vs_maps->yaw_deg);
        }
        if (g.merged_vs_maps) merged_vs_maps_t.push_back(g.merged_vs_maps->translation_m);
        consistency.insert(consistency.end(), g.merged_distances.begin(), g.merged_distances.end());
      }

    // Perception: what the run asked for and what every driver says it published.
    bool oracle = opts.perception == "oracle";
    std::string published;
    for (const auto& [a, d] : detections) {
      oracle |= d == "oracle";
      published += (published.empty() ? "" : ", ") + ("robot" + std::to_string(a) + " " + d);
    }
    const std::string perception = (opts.perception.empty() ? std::string("not stated") : opts.perception) +
                                   " (drivers published detections: " + published + ")";
    const std::string object_note = oracle ? "ORACLE: ground-truth labels / masks reached the robots; an upper bound, "
                                             "not what a robot achieves"
                                           : "perception " + perception;
    bench::BenchReport report("system");
    if (std::isfinite(opts.wall_s)) report.add("demo.wall_s", opts.wall_s, "s", true, 300.0);
    report.add("demo.inter_robot_trans_err_m", bench::mean(trans_err), "m", true, 0.5, 0.54).note =
        "mean over " + std::to_string(pairs_found) + " of " + std::to_string(pairs_possible) + " ordered pairs found";
    report.add("demo.inter_robot_yaw_err_deg", bench::mean(yaw_err), "deg", true, 2.0);
    report.add("demo.inter_robot_vs_maps_trans_err_m", bench::mean(place_vs_maps_t), "m", true, 0.15, 0.16).note =
        "place recognition's transform, horizontally (x, y), against the best rigid alignment (x, y, yaw) of the two robots' own maps (own "
        "observations replayed from their journals) over the landmarks both hold (the paper's comparison; ground truth only pairs the landmarks), mean over " +
        std::to_string(place_vs_maps_t.size()) + " ordered pairs";
    report.add("demo.inter_robot_vs_maps_yaw_err_deg", bench::mean(place_vs_maps_yaw), "deg", true);
    report.add("demo.merged_vs_maps_trans_err_m", bench::mean(merged_vs_maps_t), "m", true).note =
        "the optimizer's merged frame against the same map alignment";
    report.add("demo.merged_consistency_median_m", consistency.empty() ? NAN : bench::median(consistency), "m", true)
        .note =
        "horizontal distance between two robots' own landmarks of one real object, the peer's placed by the host's "
        "merged frame (" +
        std::to_string(consistency.size()) + " landmark pairs)";
    report.add("demo.merged_consistency_p90_m", consistency.empty() ? NAN : bench::quantile(consistency, 0.9), "m",
               true);
    report.add("demo.merged_trans_err_m", bench::mean(merged_trans_err), "m", true).note =
        "the optimizer's estimate of each merged peer's frame, after the joint solve (" +
        std::to_string(merged_trans_err.size()) + " ordered pairs)";
    report.add("demo.merged_yaw_err_deg", bench::mean(merged_yaw_err), "deg", true);
    report.add("demo.peer_trajectory_rmse_m", bench::mean(peer_rmse), "m", true).note =
        "merged peers' key poses in the host's frame against truth, no alignment";
    report.add("demo.pairs_found_fraction", pairs_possible ? double(pairs_found) / pairs_possible : 0.0, "", false, 1.0);
    report.add("demo.ate_m", bench::mean(ates), "m").note = "mean over robots of own-trajectory ATE (SE3 aligned)";
    report.add("demo.ate_anchored_m", bench::mean(anchored_ates), "m", true).note =
        "own trajectory, no alignment: the estimate placed in the world by the robot's true start";
    report.add("demo.odom_ate_m", bench::mean(odom_ates), "m").note =
        "raw odometry at the same key poses (SE3 aligned)";
    report.add("demo.odom_ate_anchored_m", bench::mean(odom_anchored_ates), "m").note =
        "raw odometry at the same key poses, no alignment: placed by the robot's true start (compare with demo.ate_anchored_m)";
    report.add("demo.precision", bench::mean(precisions), "", false, 0.95).note = object_note;
    report.add("demo.recall", bench::mean(recalls), "", false, 0.92).note = object_note;
    report.add("demo.f1", bench::mean(f1s), "", false, 0.93).note = object_note;
    // Per true class, pooled over robots (every robot's landmarks and its share of the objects).
    std::map<int, std::array<std::size_t, 4>> by_class;  // {recall TP, objects, precision TP, landmarks}
    for (const RobotFigures& f : figs) {
      for (const auto& [c, s] : f.class_recall) by_class[c][0] += s.true_positives, by_class[c][1] += s.num_gt;
      for (const auto& [c, s] : f.class_precision) by_class[c][2] += s.true_positives, by_class[c][3] += s.num_est;
    }
    for (const auto& [c, n] : by_class) {
      if (n[1] == 0) continue;  // no real object of the class near the paths
      const ClassInfo* info = classes.find(c);
      const std::string name = "demo.class." + (info ? info->name : std::to_string(c));
      if (n[3] > 0)  // (no landmark of the class: no precision to give)
        report.add(name + ".precision", double(n[2]) / n[3], "").note =
            std::to_string(n[2]) + " of " + std::to_string(n[3]) + " landmarks of the class at a real one, all robots; " + object_note;
      report.add(name + ".recall", double(n[0]) / n[1], "").note =
          std::to_string(n[0]) + " of " + std::to_string(n[1]) +
          " (robots x real objects of the class near the paths) found as the class; " + object_note;
    }
    report.add("demo.second_landmarks", bench::mean(second_shares), "", true, 0.02).note =
        "share of a robot's landmarks that are a second landmark of a real object of their class (within the match "
        "distance of one another landmark took), mean over robots; scored by simulator truth";
    report.add("demo.team_bytes", double(team_bytes), "bytes").note =
        std::to_string(traffic.messages) + " team-bus messages; IPv4 bytes on the wire (LCM, UDP and IP headers included; " +
        std::to_string(traffic.payload) + " bytes of LCM payload)";
    const double all = std::max<double>(1.0, double(team_bytes));
    report.add("demo.share.bundles", double(traffic.bundles) / all, "").note = "of the wire bytes: observation bundles";
    report.add("demo.share.maps", double(traffic.maps) / all, "").note = "object maps, whole and as changes";
    report.add("demo.share.heartbeats", double(traffic.heartbeats) / all, "");
    report.add("demo.share.acks", double(traffic.acks) / all, "");
    report.add("demo.bytes_per_landmark", bw.bytes_per_landmark, "bytes", true, 200.0, 1800.0);
    report.add("demo.bytes_per_metre", bw.bytes_per_metre, "bytes", true, 500.0, 1650.0);
    report.printTable(std::cout);
    report.writeJson(opts.out_dir + "/report.json");
    if (!opts.json.empty()) report.writeJson(opts.json);

    std::ofstream md(opts.out_dir + "/report.md");
    md << "# Team run report\n\nRun: `" << opts.run_dir << "`; ground truth: `" << opts.data_dir << "`.\n\n";
    md << "Perception: **" << perception << "**."
       << (oracle ? " **ORACLE run: ground-truth labels or masks reached the robots; every figure is an upper bound.**" : "")
       << "\n\n";
    md << frontEndRange(opts.run_dir + "/config/frontend.yaml") << "\n\n";
    md << "| figure | value | unit | target | paper | note |\n|---|---|---|---|---|---|\n";
    for (const bench::BenchResult& r : report.results())
      md << "| " << r.name << " | " << num(r.value) << " | " << r.unit << " | " << (r.target ? num(*r.target) : "-")
         << " | " << (r.paper ? num(*r.paper) : "-") << " | " << r.note << " |\n";
    md << "\nObject scores place each robot's landmarks in the world through its true start and match them "
       << "one-to-one within " << opts.match_threshold << " m (x, y): recall counts the " << visible.size()
       << " static ground-truth objects within " << opts.visible_range
       << " m of any robot's path, precision counts matches against all " << truth.objects.size()
       << " static objects.\n\n";
    md << "## Per robot\n\nATE: own trajectory against the truth, SE3-aligned and (no alignment) placed by the robot's "
          "true start; each beside the raw odometry's at the same key poses under the same alignment.\n\n";
    md << "| robot | platform | detections | key poses | ATE m, aligned: estimate / odometry | ATE m, no alignment: estimate / odometry | landmarks | precision | recall | F1 | "
          "trajectories held | bundles own / peers | update ms median / p99 |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const RobotFigures& f : figs)
      md << "| " << f.robot << " | " << truth.robot(f.robot).platform << " | " << detections[f.robot] << " | " << f.poses << " | " << num(f.ate) << " / " << num(f.odom_ate) << " | " << num(f.ate_anchored) << " / "
         << num(f.odom_ate_anchored) << " | "
         << f.landmarks << " | " << num(f.objects.overall.precision) << " | " << num(f.objects.overall.recall) << " | "
         << num(f.objects.overall.f1) << " | " << f.trajectories << " | " << f.keypose_bundles << " / "
         << f.peer_bundles << " | " << num(f.update_ms_median, 2) << " / " << num(f.update_ms_p99, 2) << " |\n";
    md << "\n### Landmarks by class\n\nEach robot's landmarks by the class it gave them: at a real object of that class, "
          "at a real object of another class only (class confusion), a second landmark of a real object of its class "
          "that another landmark took (the object mapped twice), or at no real object within "
       << opts.match_threshold
       << " m.\n\n| robot | class | landmarks | right class | other class | second landmark | nothing there |\n"
          "|---|---|---|---|---|---|---|\n";
    for (const RobotFigures& f : figs)
      for (const auto& [c, n] : f.landmark_classes) {
        const ClassInfo* info = classes.find(c);
        md << "| " << f.robot << " | " << (info ? info->name : std::to_string(c)) << " | " << n[0] << " | " << n[1]
           << " | " << n[2] << " | " << n[3] << " | " << n[4] << " |\n";
      }
    md << "\n## Inter-robot transforms\n\nPlace recognition's transform (the loop closer's last), and the optimizer's "
          "estimate of the peer's frame after merging, with the peer's key poses' RMS error in the host frame.\n\n"
          "| robot | peer | place recognition: translation m / yaw deg | optimizer: translation m / yaw deg | "
          "peer key poses RMSE m |\n|---|---|---|---|---|\n";
    for (const RobotFigures& f : figs)
      for (const auto& [b, e] : f.closures) {
        std::string opt = "not merged", rmse = "-";
        for (const auto& [pb, m] : f.merged)
          if (pb == b) opt = num(m.translation_m) + " / " + num(m.yaw_deg, 2);
        for (const auto& [pb, r] : f.peer_traj_rmse)
          if (pb == b) rmse = num(r);
        md << "| " << f.robot << " | " << b << " | " << num(e.translation_m) << " / " << num(e.yaw_deg, 2) << " | "
           << opt << " | " << rmse << " |\n";
      }
    if (pairs_found == 0) md << "| - | - | no transform found | |\n";
    md << "\nThe same transforms, horizontally (x, y and yaw; landmark heights are not comparable between robots), against the best rigid alignment of the two robots' own maps (each robot's own "
          "observations replayed from its optimizer journal) over the landmarks both hold (the paper's comparison; "
          "the ground truth only pairs the landmarks), and the merged map's consistency: the horizontal distance between the "
          "two robots' own landmarks of one real object, the peer's placed by the host's merged frame.\n\n"
          "| robot | peer | landmarks both hold | place recognition vs maps: m / deg | optimizer vs maps: m / deg | "
          "consistency median / p90 m |\n|---|---|---|---|---|---|\n";
    auto err = [](const std::optional<eval::HorizontalError>& e) {
      return e ? num(e->translation_m) + " / " + num(e->yaw_deg, 2) : std::string("-");
    };
    for (const MapAgreement& g : agreements)
      md << "| " << g.a << " | " << g.b << " | " << g.shared << " | " << err(g.place_vs_maps) << " | "
         << err(g.merged_vs_maps) << " | "
         << (g.merged_distances.empty()
                 ? std::string("-")
                 : num(bench::median(g.merged_distances)) + " / " + num(bench::quantile(g.merged_distances, 0.9)))
         << " |\n";
    md << "\n## Pictures\n\n";
    for (int a : opts.robots)
      md << "![robot" << a << "](robot" << a << "_top.png)\n![robot" << a << " oblique](robot" << a
         << "_oblique.png)\n\n";
    spdlog::info("report: {}/report.md", opts.out_dir);
    return 0;
  });
}
