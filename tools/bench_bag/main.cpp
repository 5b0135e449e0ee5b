// slide-bench-bag: how fast the sensor driver's bag input decodes an OS1-64 recording
// (64 x 1024 organised PointCloud2, Ouster's 48-byte points with per-point time, odometry at
// 100 Hz). Target: 10x real time (100 sweeps/s at 10 Hz) on one core. The bag is written first
// by tests/io/make_bags.py (python3-rosbag) into a scratch folder.
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "app/app.h"
#include "bench/report.h"
#include "bench/stats.h"
#include "clock/thread_cpu.h"
#include "io/robot_dataset.h"

int main(int argc, char** argv) {
  CLI::App app{"Bag decoding benchmark (suite 'bag')", "slide-bench-bag"};
  slide::app::CommonOptions common;
  slide::app::addCommonOptions(app, common);
  std::string json, tmp = (std::filesystem::temp_directory_path() / "slide-bench-bag").string();
  int frames = 30;
  app.add_option("--json", json, "Write the results as JSON to FILE");
  app.add_option("--frames", frames, "OS1-64 sweeps in the bag")->capture_default_str()->check(CLI::Range(2, 1000));
  app.add_option("--tmp", tmp, "Scratch folder for the bag (removed afterwards)")->capture_default_str();
  return slide::app::runApp(app, common, argc, argv, [&]() {
    std::filesystem::create_directories(tmp);
    std::cerr << "writing an OS1-64 bag of " << frames << " sweeps with python3-rosbag ...\n";
    const std::string cmd = "/usr/bin/python3 " + std::string(SLIDE_SOURCE_DIR) + "/tests/io/make_bags.py " + tmp +
                            " --only ouster --os1-frames " + std::to_string(frames);
    if (std::system(cmd.c_str()) != 0) throw std::runtime_error("failed: " + cmd);
    const std::string bag = tmp + "/ouster.bag";
    slide::bench::BenchReport report("bag");
    const std::string what = "synthetic OS1-64 bag (64x1024, 48-byte points, uncompressed, in the page cache)";
    for (bool deskew : {false, true}) {
      slide::io::DatasetOptions o;
      o.bag.cloud_topic = "/os_cloud_node/points";
      o.bag.odom_topic = "/odom";
      o.bag.deskew = deskew;
      const double c0 = slide::clock::threadCpuMs();
      const slide::io::RobotDataset d = slide::io::openRobotDataset(bag, o);
      const double open_ms = slide::clock::threadCpuMs() - c0;
      std::vector<double> ms;
      std::size_t points = 0;
      for (int pass = 0; pass < 3; ++pass)
        for (std::size_t i = 0; i < d.size(); ++i) {
          const double t0 = slide::clock::threadCpuMs();
          points += d.scan(i).size();
          ms.push_back(slide::clock::threadCpuMs() - t0);
        }
      const double med = slide::bench::median(ms);
      const std::string tag = deskew ? "os1_64.deskew" : "os1_64.decode";
      const std::string runs = "median of " + std::to_string(ms.size()) + " sweeps (3 passes), CPU time of one thread, " +
                               std::to_string(points / ms.size()) + " points/sweep; " + what;
      report.add(tag + "_ms.median", med, "ms").note = runs;
      report.add(tag + "_fps", 1000.0 / med, "frames/s", false, 100.0).note = "sweeps decoded per second; target 10x real time";
      report.add(tag + "_realtime_factor", 100.0 / med, "x", false, 10.0).note = "10 Hz sweeps";
      if (!deskew) report.add("os1_64.open_ms", open_ms, "ms").note = "index, stamps and odometry of " + std::to_string(d.size()) + " sweeps";
    }
    std::filesystem::remove_all(tmp);
    report.printTable(std::cout);
    if (!json.empty()) report.writeJson(json);
    return 0;
  });
}
