// The sensor driver on a generated dataset: inside a private network namespace (loopback
// only), lcm-logger records what the driver publishes; the driver's own --log replays with
// lcm-logplayer and is recorded again. Every log holds the odometry, scans/frames and a
// FINISHED status. Needs root (unshare -n) and the LCM tools; skipped otherwise.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include <lcm/lcm-cpp.hpp>

#include "sim/dataset_writer.h"
#include "slide/lidar_scan_t.hpp"
#include "slide/odometry_t.hpp"
#include "slide/rgbd_frame_t.hpp"
#include "slide/stream_status_t.hpp"

using namespace slide;
namespace fs = std::filesystem;

namespace {
struct LogSummary {
  std::map<std::string, int> count;
  int8_t last_state = -1;
  int last_sent = -1;
  int scan_points = 0;
  bool scan_labelled = false;
  int rgbd_width = 0, rgbd_instances = 0;
  double last_odom_x = 0;
};

LogSummary readLog(const std::string& path) {
  LogSummary s;
  lcm::LogFile log(path, "r");
  if (!log.good()) return s;
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    ++s.count[ev->channel];
    if (ev->channel == "SENSOR_STATUS") {
      stream_status_t m;
      if (m.decode(ev->data, 0, ev->datalen) > 0) s.last_state = m.state, s.last_sent = m.frames_sent;
    } else if (ev->channel == "SCAN") {
      lidar_scan_t m;
      if (m.decode(ev->data, 0, ev->datalen) > 0) s.scan_points = m.num_points, s.scan_labelled = m.has_labels;
    } else if (ev->channel == "RGBD") {
      rgbd_frame_t m;
      if (m.decode(ev->data, 0, ev->datalen) > 0) s.rgbd_width = m.intrinsics.width, s.rgbd_instances = m.num_instances;
    } else if (ev->channel == "ODOM") {
      odometry_t m;
      if (m.decode(ev->data, 0, ev->datalen) > 0) s.last_odom_x = m.pose.position[0];
    }
  }
  return s;
}

bool canRun() {
  return geteuid() == 0 && std::system("command -v unshare lcm-logger lcm-logplayer ip >/dev/null 2>&1") == 0;
}

// Runs the driver on `robot_dir` inside a fresh network namespace while lcm-logger records
// the bus into rec.lcm; then replays the driver's log (drv.lcm) with lcm-logplayer into
// replay.lcm. Returns the shell's exit status.
int runInNamespace(const fs::path& work, const fs::path& robot_dir, const std::string& extra_args) {
  const std::string url = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";
  const std::string driver = std::string(SLIDE_BINARY_DIR) + "/bin/slide-sensor-driver";
  const fs::path script = work / "run.sh";
  std::ofstream(script) << "set -e\n"
                        << "ip link set lo up\nip route add 224.0.0.0/4 dev lo\n"
                        << "cd " << work << "\n"
                        << "lcm-logger -q -f --lcm-url='" << url << "' rec.lcm & L=$!\n"
                        << "sleep 1\n"
                        << driver << " " << robot_dir << " --rate 5 --no-progress --log drv.lcm " << extra_args
                        << " --lcm-url='udpm://239.255.76.67:7667?ttl=0'\n"
                        << "sleep 0.5\nkill -INT $L; wait $L || true\n"
                        << "lcm-logger -q -f --lcm-url='" << url << "' replay.lcm & L=$!\n"
                        << "sleep 1\n"
                        << "lcm-logplayer -s 5 --lcm-url='udpm://239.255.76.67:7667?ttl=0' drv.lcm\n"
                        << "sleep 0.5\nkill -INT $L; wait $L || true\n";
  return std::system(("unshare -n bash " + script.string() + " > " + (work / "run.log").string() + " 2>&1").c_str());
}
}  // namespace

TEST(SensorDriver, LidarDatasetReachesLoggerAndLogReplays) {
  if (!canRun()) GTEST_SKIP() << "needs root, unshare, ip and the LCM tools";
  const fs::path work = fs::temp_directory_path() / ("slide_test_driver_" + std::to_string(::getpid()));
  fs::remove_all(work);
  ScenarioSpec spec;
  spec.world = "forest";
  spec.robots = 1;
  spec.frames = 12;
  spec.forest.num_trees = 200;
  spec.forest.side = 80;
  SensorOptions sensors;
  sensors.lidar = lidarModel("vlp-16");
  writeScenarioDataset(buildScenario(spec), sensors, (work / "data").string());

  // Skip the first 2 frames (start offset) and send the rest.
  ASSERT_EQ(runInNamespace(work, work / "data" / "robot0", "--start-frame 2"), 0)
      << std::ifstream(work / "run.log").rdbuf();
  for (const char* name : {"drv.lcm", "rec.lcm", "replay.lcm"}) {
    LogSummary s = readLog((work / name).string());
    SCOPED_TRACE(name);
    EXPECT_EQ(s.count["SCAN"], 10);
    EXPECT_EQ(s.count["ODOM"], 10);
    EXPECT_GE(s.count["SENSOR_STATUS"], 2);
    EXPECT_EQ(s.last_state, stream_status_t::FINISHED);
    EXPECT_EQ(s.last_sent, 10);
    EXPECT_GT(s.scan_points, 5000);
    EXPECT_TRUE(s.scan_labelled);
    EXPECT_NE(s.last_odom_x, 0.0);
  }
  fs::remove_all(work);
}

TEST(SensorDriver, RgbdDatasetFrames) {
  if (!canRun()) GTEST_SKIP() << "needs root, unshare, ip and the LCM tools";
  const fs::path work = fs::temp_directory_path() / ("slide_test_driver_rgbd_" + std::to_string(::getpid()));
  fs::remove_all(work);
  ScenarioSpec spec;
  spec.world = "indoor";
  spec.robots = 1;
  spec.frames = 3;
  SensorOptions sensors;
  sensors.sensor = "rgbd";
  writeScenarioDataset(buildScenario(spec), sensors, (work / "data").string());
  ASSERT_EQ(runInNamespace(work, work / "data" / "robot0", ""), 0) << std::ifstream(work / "run.log").rdbuf();
  for (const char* name : {"drv.lcm", "rec.lcm"}) {
    LogSummary s = readLog((work / name).string());
    SCOPED_TRACE(name);
    EXPECT_EQ(s.count["RGBD"], 3);
    EXPECT_EQ(s.count["ODOM"], 3);
    EXPECT_EQ(s.rgbd_width, 640);
    EXPECT_EQ(s.last_state, stream_status_t::FINISHED);
  }
  fs::remove_all(work);
}
