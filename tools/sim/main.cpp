// slide-sim: generates a simulated multi-robot dataset (world, robot trajectories, odometry,
// LiDAR scans or RGBD frames, ground-truth objects) in the layouts of lib/simulator/dataset_writer.h.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

#include "app/app.h"
#include "simulator/dataset_writer.h"

int main(int argc, char** argv) {
  CLI::App app{"Generate a simulated multi-robot dataset (one folder per robot plus objects.csv)", "slide-sim"};
  slide::app::CommonOptions common;
  slide::app::addCommonOptions(app, common);
  slide::simulator::ScenarioSpec spec;
  std::string out, sensor = "lidar", lidar = "os1-64", camera = "d455";
  bool force = false, quiet = false;
  unsigned threads = 0;
  app.add_option("--world", spec.world, "World: forest | urban | indoor | kitti05 | kitti07")
      ->check(CLI::IsMember(slide::simulator::worldNames()))
      ->capture_default_str();
  app.add_option("--robots", spec.robots, "Number of robots")->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--seed", spec.seed, "Random seed (same seed, same dataset)")->capture_default_str();
  app.add_option("--out", out, "Output folder")->required();
  std::vector<std::string> sensors_list;
  auto* sensor_opt =
      app.add_option("--sensor", sensor, "Sensor of every robot: lidar | rgbd")->check(CLI::IsMember({"lidar", "rgbd"}))->capture_default_str();
  app.add_option("--sensors", sensors_list, "Mixed team: one sensor per robot, e.g. lidar,rgbd,rgbd")
      ->delimiter(',')
      ->check(CLI::IsMember({"lidar", "rgbd"}))
      ->excludes(sensor_opt);
  auto* lidar_opt = app.add_option("--lidar", lidar, "LiDAR model: os1-64 | hdl-64e | vlp-16 (KITTI worlds: hdl-64e)")
      ->check(CLI::IsMember(slide::simulator::lidarModelNames()))
      ->capture_default_str();
  app.add_option("--camera", camera, "RGBD camera: d435 | d455")
      ->check(CLI::IsMember(slide::simulator::cameraModelNames()))
      ->capture_default_str();
  auto* frames = app.add_option("--frames", spec.frames, "Frames per robot (KITTI: cut each split to N frames)");
  app.add_option("--distance", spec.distance, "Metres driven per robot (procedural worlds)")
      ->excludes(frames)
      ->capture_default_str();
  app.add_option("--overlap", spec.overlap, "Share of each route on a route common to all robots (0..1)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  auto* aerial_opt = app.add_flag("--aerial", spec.aerial, "Aerial robots (altitude changes) instead of ground robots");
  app.add_option("--aerial-robots", spec.aerial_robots, "Mixed team: ids of the aerial robots, e.g. 2 (the others drive)")
      ->delimiter(',')
      ->excludes(aerial_opt);
  app.add_option("--speed", spec.speed, "Robot speed m/s (0: world default: forest 1.5, urban 2, indoor 0.8)");
  app.add_option("--rate", spec.rate, "Sensor frames per second")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--clearance", spec.clearance, "Metres kept free of objects around paths (0: world default)");
  app.add_option("--forest-layout", spec.forest.layout, "Forest stems: procedural | longleaf | finpines | spruces")
      ->check(CLI::IsMember({"procedural", "longleaf", "finpines", "spruces"}))
      ->capture_default_str();
  app.add_option("--trees", spec.forest.num_trees, "Procedural forest: number of stems")->capture_default_str();
  app.add_option("--side", spec.forest.side, "Forest: side of the square world, metres")->capture_default_str();
  app.add_option("--drift", spec.odometry.translation_drift, "Odometry drift, fraction of distance")->capture_default_str();
  app.add_option("--yaw-drift", spec.odometry.yaw_drift_deg_per_m, "Odometry yaw drift, deg per metre")
      ->capture_default_str();
  app.add_option("--data-dir", spec.data_dir, "Real data folder (KITTI poses/poles, forest inventory)");
  app.add_flag("--force", force, "Write into a non-empty output folder");
  app.add_flag("--quiet", quiet, "No progress bar");
  app.add_option("--threads", threads, "Robots generated in parallel (0: one per core)")->capture_default_str();

  return slide::app::runApp(app, common, argc, argv, [&]() {
    namespace fs = std::filesystem;
    if (fs::exists(out) && !fs::is_empty(out) && !force)
      throw std::runtime_error("output folder " + out + " is not empty (use --force to write into it)");
    if (!sensors_list.empty() && static_cast<int>(sensors_list.size()) != spec.robots)
      throw std::runtime_error("--sensors lists " + std::to_string(sensors_list.size()) + " sensors for " +
                               std::to_string(spec.robots) + " robots");
    slide::simulator::SensorOptions sensors;
    sensors.sensor = sensor;
    sensors.per_robot = sensors_list;
    if (lidar_opt->count() == 0 && spec.world.rfind("kitti", 0) == 0) lidar = "hdl-64e";  // KITTI's own sensor
    sensors.lidar = slide::simulator::lidarModel(lidar);
    sensors.camera = slide::simulator::cameraModel(camera);
    const auto t0 = std::chrono::steady_clock::now();
    const slide::simulator::Scenario sc = slide::simulator::buildScenario(spec);
    spdlog::info("world '{}': {} objects, {} scenery shapes; {} robot(s)", sc.world.name, sc.world.objects.size(),
                 sc.world.structures.size(), sc.robots.size());
    for (const auto& r : sc.robots)
      spdlog::info("robot {}: {} {} robot, {} frames, {:.0f} m", r.id, r.aerial ? "aerial" : "ground", sensors.sensorOf(r.id),
                   r.ground_truth.size(), r.ground_truth.length());
    // Progress: one line for all robots, redrawn in place on a terminal, every 10 % otherwise.
    const bool bar = !quiet && isatty(STDERR_FILENO);
    std::vector<int> done(sc.robots.size(), 0);
    int all = 0, last_decile = -1;
    for (std::size_t r = 0; r < sc.robots.size(); ++r) all += static_cast<int>(sc.robots[r].ground_truth.size());
    const auto progress = [&](int robot, int i, int n) {
      if (quiet) return;
      done[robot] = i + 1;
      int sum = 0;
      for (int d : done) sum += d;
      const int decile = all > 0 ? 10 * sum / all : 10;
      if (!bar && decile == last_decile) return;
      last_decile = decile;
      const int width = 30, filled = all > 0 ? width * sum / all : width;
      std::fprintf(stderr, "%s[%.*s%*s] %d/%d frames", bar ? "\r" : "", filled, "##############################",
                   width - filled, "", sum, all);
      for (std::size_t r = 0; r < done.size(); ++r) std::fprintf(stderr, "  r%zu %d", r, done[r]);
      std::fprintf(stderr, "%s", bar && sum < all ? "" : "\n");
      std::fflush(stderr);
      (void)n;
    };
    const slide::simulator::GenerationStats st =
        slide::simulator::writeScenarioDataset(sc, sensors, out, progress, threads);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    spdlog::info("wrote {} frames ({} points or valid depth pixels) to {} in {:.1f} s", st.frames, st.points, out, s);
    return 0;
  });
}
