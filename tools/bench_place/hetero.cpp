#include "eval/transform_error.h"
#include "hetero.h"

#include <algorithm>
#include <chrono>
#include <set>

#include <spdlog/spdlog.h>

#include "backend/backend_config.h"
#include "place/map_perturb.h"
#include "frontend/frontend_config.h"
#include "place/landmark.h"
#include "simulator/scenario.h"
#include "mapped_robot/map_robot.h"

namespace slide::bench_place {

namespace {
// Robot `r` follows robot 0's route backwards (same places, opposite heading, other start),
// `climb` metres higher and level when climb > 0; its odometry is simulated anew.
void retrace(slide::simulator::Scenario& sc, int r, double climb) {
  simulator::RobotRun& run = sc.robots.at(static_cast<std::size_t>(r));
  const std::vector<Pose>& route = sc.robots.at(0).ground_truth.poses;
  run.ground_truth.times = sc.robots.at(0).ground_truth.times;
  run.ground_truth.poses.clear();
  for (auto it = route.rbegin(); it != route.rend(); ++it) {
    Pose T = *it;
    T.linear() = T.linear() * rotZ(M_PI);
    if (climb > 0) {
      const Eigen::Vector3d t = T.translation();
      T = poseFromXyzYaw(t.x(), t.y(), t.z() + climb, yawOf(T.linear()));
    }
    run.ground_truth.poses.push_back(T);
  }
  std::mt19937_64 rng(sc.spec.seed * 7919 + 104729 * (run.id + 1) + 1);
  run.odometry = simulator::simulateOdometry(run.ground_truth.poses, sc.spec.odometry, rng);
  run.T_world_odom = simulator::odometryOrigin(run.ground_truth.poses.front());
}

// Ids of true objects that a landmark of `map` (odometry frame T_world_odom) lies near:
// Within the class's association distance (horizontal), as the front-end benchmark scores maps.
std::set<std::int64_t> trueObjectsOf(const std::vector<Object>& map, const Pose& T_world_odom,
                                     const simulator::World& world, const ClassTable& classes, int& hits,
                                     double& median_err) {
  std::set<std::int64_t> ids;
  std::vector<double> errs;
  hits = 0;
  for (const Object& o : map) {
    const Eigen::Vector3d p = T_world_odom * o.position();
    const ClassInfo* info = classes.find(o.class_id);
    double best = info ? info->association_distance : 1.0, nearest = 1e9;
    std::int64_t id = -1;
    for (const auto& g : world.objects) {
      if (g.object.class_id != o.class_id) continue;
      const double d = (g.object.position() - p).head<2>().norm();
      nearest = std::min(nearest, d);
      if (d < best) best = d, id = g.object.id;
    }
    if (id >= 0) ++hits, ids.insert(id), errs.push_back(best);
    spdlog::debug("  class {} at ({:.1f}, {:.1f}, {:.1f}): true object {} (nearest of its class {:.2f} m)", o.class_id,
                  p.x(), p.y(), p.z(), id, nearest);
    // Cuboids: heading (world frame) and extents against the associated true box.
    const auto* box = std::get_if<Cuboid>(&o.model);
    const io::GroundTruthObject* truth = nullptr;
    for (const auto& g : world.objects)
      if (g.object.id == id) truth = &g;
    const auto* true_box = truth ? std::get_if<Cuboid>(&truth->object.model) : nullptr;
    if (box && true_box) {
      // x along the longer side on both (a box with yaw + 90 deg and swapped extents is the same box).
      auto longYaw = [](double yaw, const Eigen::Vector3d& d) { return d.x() >= d.y() ? yaw : yaw + M_PI / 2; };
      const double yaw = longYaw(yawOf(T_world_odom.linear() * box->pose.linear()), box->dims);
      const double true_yaw = longYaw(yawOf(true_box->pose.linear()), true_box->dims);
      spdlog::debug("    box yaw {:.0f} deg dims ({:.1f}, {:.1f}, {:.1f}); true yaw {:.0f} deg dims ({:.1f}, {:.1f}, {:.1f}); "
                    "yaw error of the long side {:.0f} deg", yaw * 180 / M_PI, box->dims.x(), box->dims.y(), box->dims.z(),
                    true_yaw * 180 / M_PI, true_box->dims.x(), true_box->dims.y(), true_box->dims.z(),
                    std::abs(wrapAngle(2 * (yaw - true_yaw))) * 90 / M_PI);
      const Eigen::Vector3d e = true_box->pose.linear().transpose() * (p - true_box->pose.translation());
      spdlog::debug("    position error along the true box's x {:.2f} m, y {:.2f} m", e.x(), e.y());
    }
  }
  std::sort(errs.begin(), errs.end());
  median_err = errs.empty() ? 0.0 : errs[errs.size() / 2];
  return ids;
}

HeteroMethod place(place::PlaceMethod m, const std::vector<place::Landmark>& a, const std::vector<place::Landmark>& b,
                   const Pose& truth, const place::PlaceConfig& config, int repeats) {
  HeteroMethod out;
  std::vector<double> ms;
  place::PlaceResult first;
  for (int k = 0; k < repeats; ++k) {
    place::PlaceResult r = place::recognizePlace(m, a, b, config);
    ms.push_back(r.cpu_ms);
    if (k == 0) first = std::move(r);
  }
  std::sort(ms.begin(), ms.end());
  out.cpu_ms = ms[ms.size() / 2];
  out.found = first.found;
  out.reason = first.reason;
  out.inliers = first.inliers.size();
  if (first.found) {
    const eval::TransformError e = eval::transformError(first.T_a_b, truth);
    out.trans_err_m = e.translation_m;
    out.yaw_err_deg = e.yaw_deg;
  }
  return out;
}
}  // namespace

HeteroSpec heteroLidarRgbd(std::uint64_t seed) {
  HeteroSpec s;
  s.name = "hetero_lidar_rgbd";
  s.world = "indoor";
  s.sensor_a = "lidar:os1-64";
  s.sensor_b = "rgbd:d455";
  s.distance = 45;
  s.overlap = 0.6;
  s.rate = 2;
  s.seed = seed;
  s.description = "indoor office floor; A: OS1-64 LiDAR (labelled segmentation), B: D455 RGBD (instance masks), "
                  "both 0.5 m up";
  return s;
}

HeteroSpec heteroAerialGround(std::uint64_t seed) {
  HeteroSpec s;
  s.name = "hetero_aerial_ground";
  s.world = "urban";
  s.sensor_a = "rgbd:d455";
  s.sensor_b = "rgbd:d455";
  s.pitch_a_deg = 10;
  s.pitch_b_deg = 50;
  s.climb_b = 4.0;
  s.retrace_b = true;
  s.distance = 60;
  s.overlap = 0.7;
  s.rate = 2;
  s.seed = seed;
  s.description = "urban parking lot; A: ground robot, D455 1 m up pitched 10 deg down; B: aerial robot, D455 5 m up "
                  "pitched 50 deg down, flying A's route backwards (car roofs against car fronts and sides)";
  return s;
}

HeteroFigures runHetero(const HeteroSpec& spec, const place::PlaceConfig& config, int repeats) {
  const auto t0 = std::chrono::steady_clock::now();
  simulator::ScenarioSpec ss;
  ss.world = spec.world;
  ss.robots = 2;
  ss.seed = spec.seed;
  ss.distance = spec.distance;
  ss.overlap = spec.overlap;
  ss.rate = spec.rate;
  slide::simulator::Scenario sc = simulator::buildScenario(ss);
  if (spec.retrace_b) retrace(sc, 1, spec.climb_b);

  mapped_robot::MappingSetup setup{ClassTable::loadDefault(), frontend::loadDefaultFrontendConfig(),
                                   backend::loadBackendConfig(std::string(SLIDE_SOURCE_DIR) + "/config/backend.yaml"),
                                   spec.seed, std::nullopt};
  // What a robot has: the detection emulator's labels / masks, not the simulator's ground truth.
  setup.emulator = emulator::loadDetectionEmulatorConfig(std::string(SLIDE_SOURCE_DIR) + "/config/detections.yaml");
  mapped_robot::SensorRig rig_a = mapped_robot::parseSensorRig(spec.sensor_a),
                          rig_b = mapped_robot::parseSensorRig(spec.sensor_b);
  rig_a.T_body_sensor = mapped_robot::pitchedMount(spec.pitch_a_deg);
  rig_b.T_body_sensor = mapped_robot::pitchedMount(spec.pitch_b_deg);
  const mapped_robot::RobotMapping a = mapped_robot::mapRobot(sc, 0, rig_a, setup);
  const mapped_robot::RobotMapping b = mapped_robot::mapRobot(sc, 1, rig_b, setup);

  HeteroFigures f;
  f.objects_a = static_cast<int>(a.objects.size());
  f.objects_b = static_cast<int>(b.objects.size());
  f.frames_a = a.frames, f.frames_b = b.frames;
  f.keyposes_a = a.keyposes, f.keyposes_b = b.keyposes;
  f.map_cpu_s_a = a.sim_cpu_s + a.frontend_cpu_s + a.backend_cpu_s;
  f.map_cpu_s_b = b.sim_cpu_s + b.frontend_cpu_s + b.backend_cpu_s;
  const std::set<std::int64_t> ta = trueObjectsOf(a.objects, sc.robots[0].T_world_odom, sc.world, setup.classes, f.true_a, f.err_a);
  const std::set<std::int64_t> tb = trueObjectsOf(b.objects, sc.robots[1].T_world_odom, sc.world, setup.classes, f.true_b, f.err_b);
  for (auto id : tb) f.shared += ta.count(id);

  const std::vector<place::Landmark> la = place::landmarksOf(ObjectMap(a.objects)),
                                     lb = place::landmarksOf(ObjectMap(b.objects));
  const Pose truth = sc.robots[0].T_world_odom.inverse() * sc.robots[1].T_world_odom;
  f.slidegraph = place(place::PlaceMethod::SlideGraph, la, lb, truth, config, repeats);
  f.slidematch = place(place::PlaceMethod::SlideMatch, la, lb, truth, config, repeats);
  f.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return f;
}

}  // namespace slide::bench_place
