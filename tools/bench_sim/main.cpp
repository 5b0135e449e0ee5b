// slide-bench-sim: simulator speed. One 64-beam scan of a 1,000-tree forest (target 20 ms on
// one core), other sensors for reference, and a 3-robot, 1 km forest mission written to disk
// (target 2 minutes).
#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <thread>

#include "app/app.h"
#include "bench/report.h"
#include "bench/stats.h"
#include "clock/thread_cpu.h"
#include "simulator/dataset_writer.h"

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }
double processCpuS() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Simulator benchmark (suite 'sim')", "slide-bench-sim"};
  slide::app::CommonOptions common;
  slide::app::addCommonOptions(app, common);
  std::string json, tmp = (std::filesystem::temp_directory_path() / "slide-bench-sim").string();
  int repeats = 20;
  bool skip_mission = false;
  app.add_option("--json", json, "Write the results as JSON to FILE");
  app.add_option("--repeats", repeats, "Scans per timing")->capture_default_str();
  app.add_option("--tmp", tmp, "Scratch folder for the mission run (removed afterwards)")->capture_default_str();
  app.add_flag("--skip-mission", skip_mission, "Skip the 1 km mission (takes up to a few minutes)");
  return slide::app::runApp(app, common, argc, argv, [&]() {
    slide::bench::BenchReport report("sim");
    slide::simulator::ForestParams fp;
    fp.num_trees = 1000;
    fp.side = 160;
    const slide::simulator::World forest = slide::simulator::makeForestWorld(fp, 1);
    const auto tb = Clock::now();
    const slide::simulator::RayCaster caster(forest);
    report.add("forest.caster_build_ms", msSince(tb), "ms").note = "1,000 trunks + crowns + bushes";

    auto timeScans = [&](const slide::simulator::LidarModel& model, const std::string& name,
                         std::optional<double> target) {
      std::vector<double> ms;
      std::size_t points = 0;
      std::mt19937_64 rng(7);
      for (int i = 0; i < repeats; ++i) {
        const slide::Pose T = slide::poseFromXyzYaw(-40 + 4.0 * i, 3.0 * (i % 5) - 6, forest.terrain.height(-40 + 4.0 * i, 0) + 0.8, 0.3 * i);
        const double c0 = slide::clock::threadCpuMs();
        const slide::io::LabelledScan scan = slide::simulator::simulateLidarScan(caster, T, model, rng);
        ms.push_back(slide::clock::threadCpuMs() - c0);
        points += scan.size();
      }
      report.add("forest.scan_ms." + name, slide::bench::median(ms), "ms", true, target).note =
          "CPU time, median of " + std::to_string(repeats) + " scans, " + std::to_string(points / repeats) + " points/scan";
    };
    timeScans(slide::simulator::lidarModel("os1-64"), "os1_64", 20.0);
    timeScans(slide::simulator::lidarModel("hdl-64e"), "hdl_64e", std::nullopt);
    timeScans(slide::simulator::lidarModel("vlp-16"), "vlp_16", std::nullopt);
    {
      std::vector<double> ms;
      std::mt19937_64 rng(3);
      const slide::simulator::CameraModel cam = slide::simulator::cameraModel("d455");
      for (int i = 0; i < std::max(3, repeats / 4); ++i) {
        const double c0 = slide::clock::threadCpuMs();
        slide::simulator::renderRgbd(
            caster, slide::poseFromXyzYaw(-30 + 5.0 * i, 0, forest.terrain.height(-30 + 5.0 * i, 0) + 0.8, 0.5 * i),
            cam, rng);
        ms.push_back(slide::clock::threadCpuMs() - c0);
      }
      report.add("forest.rgbd_frame_ms.d455", slide::bench::median(ms), "ms").note =
          "640x480, CPU time, median of " + std::to_string(ms.size());
    }
    if (!skip_mission) {
      slide::simulator::ScenarioSpec spec;
      spec.world = "forest";
      spec.robots = 3;
      spec.distance = 1000.0 / 3;
      spec.forest.num_trees = 1000;
      spec.forest.side = 160;
      const auto t0 = Clock::now();
      const double cpu0 = processCpuS();
      const slide::simulator::Scenario sc = slide::simulator::buildScenario(spec);
      const slide::simulator::GenerationStats st =
          slide::simulator::writeScenarioDataset(sc, slide::simulator::SensorOptions{}, tmp);
      const double s = msSince(t0) / 1000.0;  // wall time: the target is wall-clock
      const double cpu = processCpuS() - cpu0;
      std::filesystem::remove_all(tmp);
      report.add("forest.mission_s", s, "s", true, 120.0).note =
          "3 robots x 333 m, OS1-64 at 10 Hz, 1.5 m/s: " + std::to_string(st.frames) + " scans written";
      report.add("forest.mission_cpu_s", cpu, "s").note =
          "CPU time of all threads (" + std::to_string(std::thread::hardware_concurrency()) + " cores; wall time suffers on a shared machine)";
      report.add("forest.mission_scan_ms", 1000.0 * s / std::max<std::size_t>(1, st.frames), "ms").note =
          "mean per scan including writing";
    }
    report.printTable(std::cout);
    if (!json.empty()) report.writeJson(json);
    return 0;
  });
}
