// The sensor driver on hostile dataset files (issue 16 findings 3 and 9): a times.txt that
// jumps 100000 s is replayed with a bounded pause and SIGTERM ends any wait at once; a scan
// frame it cannot read is dropped, named in its log, and the replay goes on. No bus is opened
// (--no-publish, the driver's own log is read back). Each test runs under an alarm.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <thread>

#include "simulator/dataset_writer.h"
#include "simulator/scenario.h"
#include "slide/stream_status_t.hpp"

#include "watchdog.h"

using namespace slide;
namespace fs = std::filesystem;

using slide::test::secondsSince;
using slide::test::Watchdog;

namespace {
// A 4-frame simulated LiDAR dataset; returns the robot folder.
fs::path smallDataset(const fs::path& work) {
  simulator::ScenarioSpec spec;
  spec.world = "forest";
  spec.robots = 1;
  spec.frames = 4;
  spec.forest.num_trees = 60;
  spec.forest.side = 40;
  simulator::SensorOptions sensors;
  sensors.lidar = simulator::lidarModel("vlp-16");
  simulator::writeScenarioDataset(simulator::buildScenario(spec), sensors, (work / "data").string());
  return work / "data" / "robot0";
}

// Runs the driver (no bus, only its log) and returns its exit status; kills it with SIGTERM
// after `term_after_s` when positive.
int runDriver(const fs::path& robot, const fs::path& work, const std::string& extra, double term_after_s = 0) {
  const std::string cmd = std::string(SLIDE_BINARY_DIR) + "/bin/slide-sensor-driver " + robot.string() +
                          " --no-progress --no-publish --log " + (work / "drv.lcm").string() + " " + extra +
                          " 2>" + (work / "drv.err").string();
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", ("exec " + cmd).c_str(), nullptr);
    _exit(127);
  }
  if (term_after_s > 0) {
    std::this_thread::sleep_for(std::chrono::duration<double>(term_after_s));
    kill(pid, SIGTERM);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<stream_status_t> statuses(const fs::path& log_path) {
  std::vector<stream_status_t> out;
  lcm::LogFile log(log_path.string(), "r");
  if (!log.good()) return out;
  while (const lcm::LogEvent* ev = log.readNextEvent())
    if (ev->channel == "SENSOR_STATUS") {
      stream_status_t m;
      if (m.decode(ev->data, 0, ev->datalen) == ev->datalen) out.push_back(m);
    }
  return out;
}

void jumpTimes(const fs::path& robot, double jump_s) {
  std::ifstream in(robot / "times.txt");
  std::vector<double> t;
  for (double v; in >> v;) t.push_back(v);
  std::ofstream out(robot / "times.txt");
  out.precision(6);
  out << std::fixed;
  for (std::size_t i = 0; i < t.size(); ++i) out << (i >= 2 ? t[i] + jump_s : t[i]) << "\n";
  // The odometry of the recording jumps with it (frames are only replayed with a pose).
  std::ifstream odom_in(robot / "odom.txt");
  std::vector<std::string> lines;
  for (std::string l; std::getline(odom_in, l);) lines.push_back(l);
  std::ofstream odom(robot / "odom.txt");
  odom.precision(6);
  odom << std::fixed;
  for (const std::string& l : lines) {
    std::istringstream ls(l);
    double time;
    if (!(ls >> time)) {
      odom << l << "\n";
      continue;
    }
    std::string rest;
    std::getline(ls, rest);
    odom << (time > t[1] + 1e-4 ? time + jump_s : time) << rest << "\n";
  }
}
}  // namespace

TEST(HostileValues, SensorDriverBoundsAJumpInFrameTimesAndStaysResponsive) {
  Watchdog dog(120);
  const fs::path work = fs::temp_directory_path() / ("slide_hostile_drv_" + std::to_string(getpid()));
  fs::remove_all(work);
  const fs::path robot = smallDataset(work);
  ASSERT_TRUE(fs::exists(robot / "times.txt"));
  jumpTimes(robot, 100000.0);  // the 28-hour pause of issue 16
  std::ofstream(work / "drv.yaml") << "sensor_driver:\n  max_gap_s: 0.5\n";
  auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(runDriver(robot, work, "--rate 1 --config " + (work / "drv.yaml").string()), 0);
  EXPECT_LT(secondsSince(t0), 10.0);
  auto st = statuses(work / "drv.lcm");
  ASSERT_FALSE(st.empty());
  EXPECT_EQ(st.back().state, stream_status_t::FINISHED);
  EXPECT_EQ(st.back().frames_sent, 4);
  // With the default bound (10 s) the pause is still long: SIGTERM must end it at once.
  fs::remove(work / "drv.lcm");
  t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(runDriver(robot, work, "--rate 1", 2.0), 130);
  EXPECT_LT(secondsSince(t0), 4.0);
  fs::remove_all(work);
}

TEST(HostileValues, SensorDriverDropsABadFrameNamesItAndGoesOn) {
  Watchdog dog(120);
  const fs::path work = fs::temp_directory_path() / ("slide_hostile_bad_" + std::to_string(getpid()));
  fs::remove_all(work);
  const fs::path robot = smallDataset(work);
  std::vector<fs::path> scans;
  for (const auto& e : fs::recursive_directory_iterator(robot))
    if (e.path().extension() == ".bin") scans.push_back(e.path());
  std::sort(scans.begin(), scans.end());
  ASSERT_EQ(scans.size(), 4u);
  std::ofstream(scans[2], std::ios::trunc) << "bad";  // 3 bytes: not a whole point
  EXPECT_EQ(runDriver(robot, work, "--rate 0"), 0);
  const auto st = statuses(work / "drv.lcm");
  ASSERT_FALSE(st.empty());
  EXPECT_EQ(st.back().state, stream_status_t::FINISHED);
  EXPECT_EQ(st.back().frames_sent, 3);  // the other frames are not lost
  std::ifstream err(work / "drv.err");
  std::stringstream e;
  e << err.rdbuf();
  EXPECT_NE(e.str().find(scans[2].filename().string()), std::string::npos) << e.str();
  fs::remove_all(work);
}
