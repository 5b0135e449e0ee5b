#include "simulator/scenario.h"

#include <algorithm>
#include <stdexcept>

#include "io/kitti_poses.h"
#include "simulator/indoor_world.h"
#include "simulator/kitti_world.h"
#include "simulator/urban_world.h"

namespace slide::simulator {

std::vector<std::string> worldNames() { return {"forest", "urban", "indoor", "kitti05", "kitti07"}; }

std::vector<std::pair<int, int>> kittiSplits(const std::string& world) {
  if (world == "kitti07") return {{0, 600}, {400, 1000}, {500, 1100}};
  if (world == "kitti05") return {{0, 1000}, {700, 2000}, {1600, 2760}};
  throw std::invalid_argument("no KITTI splits for world '" + world + "'");
}

namespace {
std::string dataDir(const ScenarioSpec& s) { return s.data_dir.empty() ? std::string(SLIDE_DATA_DIR) : s.data_dir; }

void addOdometry(Scenario& sc) {
  for (RobotRun& r : sc.robots) {
    std::mt19937_64 rng(sc.spec.seed * 7919 + 104729 * (r.id + 1));
    r.odometry = simulateOdometry(r.ground_truth.poses, sc.spec.odometry, rng);
    if (!r.ground_truth.poses.empty()) r.T_world_odom = odometryOrigin(r.ground_truth.poses.front());
  }
}

Scenario buildKitti(const ScenarioSpec& spec) {
  const std::string seq = spec.world.substr(5);
  const std::string dir = dataDir(spec) + "/kitti";
  const std::vector<Pose> lidar =
      io::kittiLidarPoses(io::readKittiPoses(dir + "/poses/" + seq + ".txt"), io::kittiVeloToCamTr0410());
  const std::vector<double> times = io::readKittiTimes(dir + "/poses/times_" + seq + ".txt");
  if (times.size() != lidar.size()) throw std::invalid_argument("KITTI " + seq + ": times and poses differ in length");
  Scenario sc;
  sc.spec = spec;
  sc.world = makeKittiWorld(lidar, dir + "/poles/" + seq + ".csv", spec.seed);
  sc.world.name = spec.world;
  const auto splits = kittiSplits(spec.world);
  const int n = spec.robots;
  for (int r = 0; r < n; ++r) {
    auto [first, last] = splits[r % splits.size()];
    last = std::min<int>(last, static_cast<int>(lidar.size()));
    if (spec.frames > 0) last = std::min(last, first + spec.frames);
    RobotRun run;
    run.id = r;
    run.first_source_frame = first;
    for (int i = first; i < last; ++i) {
      run.ground_truth.times.push_back(times[i]);
      run.ground_truth.poses.push_back(lidar[i]);
    }
    sc.robots.push_back(run);
  }
  addOdometry(sc);
  return sc;
}
}  // namespace

bool isAerial(const ScenarioSpec& spec, int id) {
  return spec.aerial || std::find(spec.aerial_robots.begin(), spec.aerial_robots.end(), id) != spec.aerial_robots.end();
}

Scenario buildScenario(const ScenarioSpec& spec) {
  if (spec.robots < 1) throw std::invalid_argument("robots must be at least 1");
  for (int id : spec.aerial_robots)
    if (id < 0 || id >= spec.robots)
      throw std::invalid_argument("aerial robot " + std::to_string(id) + " is not in the team (robots 0.." +
                                  std::to_string(spec.robots - 1) + ")");
  if (spec.rate <= 0) throw std::invalid_argument("rate must be positive");
  if (spec.world == "kitti05" || spec.world == "kitti07") return buildKitti(spec);

  Scenario sc;
  sc.spec = spec;
  MotionParams motion;
  motion.rate = spec.rate;
  double ground_height = 0, aerial_height = 0;  // sensor height above the terrain, or mean altitude
  if (spec.world == "forest") {
    ForestParams fp = spec.forest;
    if (fp.inventory_dir.empty()) fp.inventory_dir = dataDir(spec) + "/forest_inventory";
    sc.world = makeForestWorld(fp, spec.seed);
    motion.speed = 1.5;
    ground_height = 0.8, aerial_height = 3.0;
  } else if (spec.world == "urban") {
    sc.world = makeUrbanWorld(UrbanParams{}, spec.seed);
    motion.speed = 2.0;
    ground_height = 1.0, aerial_height = 4.0;
  } else if (spec.world == "indoor") {
    sc.world = makeIndoorWorld(IndoorParams{}, spec.seed);
    motion.speed = 0.8;
    ground_height = 0.5, aerial_height = 1.4;
    motion.altitude_amplitude = 0.5;
    motion.altitude_wavelength = 10;
    motion.corner_radius = 0.5;
  } else {
    throw std::invalid_argument("unknown world '" + spec.world + "' (forest, urban, indoor, kitti05, kitti07)");
  }
  if (spec.speed > 0) motion.speed = spec.speed;
  const double clearance = spec.clearance > 0 ? spec.clearance : spec.world == "indoor" ? 0.5 : 1.2;
  const double length = spec.frames > 0 ? spec.frames * motion.speed / motion.rate : spec.distance;
  std::mt19937_64 rng(spec.seed * 31 + 17);
  const auto routes = planRoutes(sc.world.routes, spec.robots, length, spec.overlap, rng);
  for (int r = 0; r < spec.robots; ++r) {
    RobotRun run;
    run.id = r;
    run.aerial = isAerial(spec, r);
    motion.aerial = run.aerial;
    motion.height = run.aerial ? aerial_height : ground_height;
    run.ground_truth = followRoute(routes[r], sc.world.terrain, motion, length, spec.frames);
    std::vector<Eigen::Vector2d> driven;
    for (const Pose& p : run.ground_truth.poses) driven.push_back(p.translation().head<2>());
    // A ground robot passes under crowns; what hangs lower than a metre above its sensor is cleared.
    sc.world.clearAlong(driven, clearance, {label::kBuilding}, motion.height + 1.0);
    sc.robots.push_back(run);
  }
  addOdometry(sc);
  return sc;
}

}  // namespace slide::simulator
