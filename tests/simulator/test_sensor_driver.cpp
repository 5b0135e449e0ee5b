// The sensor driver on a generated dataset: inside a private network namespace (loopback
// only), lcm-logger records what the driver publishes; the driver's own --log replays with
// lcm-logplayer and is recorded again. Every log holds the odometry, scans/frames and a
// FINISHED status. Needs root (unshare -n) and the LCM tools; skipped otherwise.
// Without a namespace (--no-publish --log): what the driver publishes in each detection mode --
// by default no ground-truth labels or masks at all.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include <lcm/lcm-cpp.hpp>

#include "io/kitti_scan.h"
#include "io/rgbd_files.h"
#include "sensor_driver_node.h"
#include "simulator/dataset_writer.h"
#include "slide/lidar_scan_t.hpp"
#include "slide/odometry_t.hpp"
#include "slide/rgbd_frame_t.hpp"
#include "slide/stream_status_t.hpp"

using namespace slide;
namespace fs = std::filesystem;

namespace {
// One VLP-16 robot in a small forest, `frames` frames, written to work/data/robot0.
void writeSmallForest(const fs::path& work, int frames) {
  simulator::ScenarioSpec spec;
  spec.world = "forest";
  spec.robots = 1;
  spec.frames = frames;
  spec.forest.num_trees = 200;
  spec.forest.side = 80;
  simulator::SensorOptions sensors;
  sensors.lidar = simulator::lidarModel("vlp-16");
  simulator::writeScenarioDataset(simulator::buildScenario(spec), sensors, (work / "data").string());
}
struct LogSummary {
  std::map<std::string, int> count;
  int8_t last_state = -1;
  int last_sent = -1;
  int scan_points = 0;
  bool scan_labelled = false;
  int rgbd_width = 0, rgbd_instances = 0;
  double last_odom_x = 0;
};

// Counts one message of the driver's into `s`.
void count(LogSummary& s, const std::string& channel, const void* data, int size) {
  ++s.count[channel];
  if (channel == "SENSOR_STATUS") {
    stream_status_t m;
    if (m.decode(data, 0, size) > 0) s.last_state = m.state, s.last_sent = m.frames_sent;
  } else if (channel == "SCAN") {
    lidar_scan_t m;
    if (m.decode(data, 0, size) > 0) s.scan_points = m.num_points, s.scan_labelled = m.has_labels;
  } else if (channel == "RGBD") {
    rgbd_frame_t m;
    if (m.decode(data, 0, size) > 0) s.rgbd_width = m.intrinsics.width, s.rgbd_instances = m.num_instances;
  } else if (channel == "ODOM") {
    odometry_t m;
    if (m.decode(data, 0, size) > 0) s.last_odom_x = m.pose.position[0];
  }
}

LogSummary readLog(const std::string& path) {
  LogSummary s;
  lcm::LogFile log(path, "r");
  if (!log.good()) return s;
  while (const lcm::LogEvent* ev = log.readNextEvent()) count(s, ev->channel, ev->data, ev->datalen);
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
  writeSmallForest(work, 12);

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
    EXPECT_FALSE(s.scan_labelled);  // by default the driver publishes no labels
    EXPECT_NE(s.last_odom_x, 0.0);
  }
  fs::remove_all(work);
}

// Without a bus or a process: the driver's node replays into a publisher given to it.
TEST(SensorDriverNode, ReplaysIntoItsPublisherAndStopsWhenAsked) {
  const fs::path work = fs::temp_directory_path() / ("slide_test_driver_node_" + std::to_string(::getpid()));
  fs::remove_all(work);
  writeSmallForest(work, 4);
  const io::RobotDataset d = io::openRobotDataset((work / "data" / "robot0").string(), io::DatasetOptions{});
  ReplayOptions opt;
  opt.rate = 0;
  opt.progress = false;
  const FramePerception perception(DetectionSource::None, {}, opt.robot);
  auto sinkInto = [](LogSummary& s) {
    return MessageSink([&s](const std::string& channel, const std::vector<uint8_t>& b) {
      count(s, channel, b.data(), static_cast<int>(b.size()));
      return true;
    }, "");
  };
  LogSummary s;
  MessageSink sink = sinkInto(s);
  StreamProgress progress;
  EXPECT_EQ(replayDataset(d, opt, perception, sink, [] { return false; }, progress), 4);
  EXPECT_EQ(s.count["SCAN"], 4);
  EXPECT_EQ(s.count["ODOM"], 4);
  EXPECT_EQ(s.last_state, stream_status_t::FINISHED);
  EXPECT_EQ(s.last_sent, 4);
  EXPECT_FALSE(s.scan_labelled);

  LogSummary stopped;
  MessageSink sink2 = sinkInto(stopped);
  int polls = 0;
  replayDataset(d, opt, perception, sink2, [&] { return ++polls > 2; }, progress);  // stopped early: no FINISHED
  EXPECT_LT(stopped.count["SCAN"], 4);
  EXPECT_NE(stopped.last_state, stream_status_t::FINISHED);
  fs::remove_all(work);
}

TEST(SensorDriver, RgbdDatasetFrames) {
  if (!canRun()) GTEST_SKIP() << "needs root, unshare, ip and the LCM tools";
  const fs::path work = fs::temp_directory_path() / ("slide_test_driver_rgbd_" + std::to_string(::getpid()));
  fs::remove_all(work);
  simulator::ScenarioSpec spec;
  spec.world = "indoor";
  spec.robots = 1;
  spec.frames = 3;
  simulator::SensorOptions sensors;
  sensors.sensor = "rgbd";
  simulator::writeScenarioDataset(simulator::buildScenario(spec), sensors, (work / "data").string());
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

namespace {
struct Published {
  std::vector<lidar_scan_t> scans;
  std::vector<rgbd_frame_t> frames;
  std::vector<std::string> status_detections;
};

Published runLogOnly(const fs::path& work, const fs::path& robot_dir, const std::string& args) {
  const std::string driver = std::string(SLIDE_BINARY_DIR) + "/bin/slide-sensor-driver";
  const fs::path log = work / "only.lcm";
  fs::remove(log);
  const std::string cmd = driver + " " + robot_dir.string() + " --rate 0 --no-progress --no-publish --log " + log.string() +
                          " " + args + " > " + (work / "driver.log").string() + " 2>&1";
  Published p;
  if (std::system(cmd.c_str()) != 0) return p;
  lcm::LogFile f(log.string(), "r");
  while (const lcm::LogEvent* ev = f.readNextEvent()) {
    if (ev->channel == "SCAN") {
      lidar_scan_t m;
      if (m.decode(ev->data, 0, ev->datalen) > 0) p.scans.push_back(m);
    } else if (ev->channel == "RGBD") {
      rgbd_frame_t m;
      if (m.decode(ev->data, 0, ev->datalen) > 0) p.frames.push_back(m);
    } else if (ev->channel == "SENSOR_STATUS") {
      stream_status_t m;
      if (m.decode(ev->data, 0, ev->datalen) > 0) p.status_detections.push_back(m.detections);
    }
  }
  return p;
}

std::string driverLog(const fs::path& work) {
  std::ifstream in(work / "driver.log");
  return std::string(std::istreambuf_iterator<char>(in), {});
}
}  // namespace

TEST(SensorDriver, PublishesNoGroundTruthUnlessAskedForOracle) {
  const fs::path work = fs::temp_directory_path() / ("slide_test_driver_modes_" + std::to_string(::getpid()));
  fs::remove_all(work);
  writeSmallForest(work, 4);
  const fs::path robot = work / "data" / "robot0";
  std::vector<io::LabelledScan> truth;
  for (int k = 0; k < 4; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "velodyne/%06d.bin", k);
    truth.push_back(io::readLabelledScan((robot / name).string()));
    ASSERT_TRUE(truth.back().hasLabels());
  }

  // Default: raw points only.
  Published none = runLogOnly(work, robot, "");
  ASSERT_EQ(none.scans.size(), 4u) << driverLog(work);
  for (const auto& m : none.scans) {
    EXPECT_FALSE(m.has_labels);
    EXPECT_EQ(m.num_labels, 0);
    EXPECT_TRUE(m.semantic.empty() && m.instance.empty());
  }
  for (const auto& d : none.status_detections) EXPECT_EQ(d, "none");

  // Emulated: classes but no instance ids, and not the ground truth.
  Published emu = runLogOnly(work, robot, "--detections emulated");
  ASSERT_EQ(emu.scans.size(), 4u) << driverLog(work);
  long differ = 0, total = 0;
  for (std::size_t k = 0; k < emu.scans.size(); ++k) {
    const auto& m = emu.scans[k];
    ASSERT_TRUE(m.has_labels);
    ASSERT_EQ(m.semantic.size(), truth[k].size());
    for (auto id : m.instance) ASSERT_EQ(id, 0);
    for (std::size_t i = 0; i < truth[k].size(); ++i) differ += m.semantic[i] != truth[k].semantic[i], ++total;
  }
  EXPECT_GT(differ, total / 200) << "emulated labels equal the ground truth";
  for (const auto& d : emu.status_detections) EXPECT_EQ(d, "emulated");

  // Oracle, asked for by name: the ground truth, and the log says so loudly.
  Published oracle = runLogOnly(work, robot, "--oracle-labels");
  ASSERT_EQ(oracle.scans.size(), 4u) << driverLog(work);
  EXPECT_NE(driverLog(work).find("ORACLE"), std::string::npos);
  for (std::size_t k = 0; k < oracle.scans.size(); ++k) {
    ASSERT_TRUE(oracle.scans[k].has_labels);
    EXPECT_EQ(std::vector<uint16_t>(oracle.scans[k].instance.begin(), oracle.scans[k].instance.end()), truth[k].instance);
  }
  for (const auto& d : oracle.status_detections) EXPECT_EQ(d, "oracle");
  EXPECT_TRUE(runLogOnly(work, robot, "--oracle-labels --detections emulated").scans.empty());  // contradiction: an error
  fs::remove_all(work);
}

TEST(SensorDriver, RgbdMasksOnlyEmulatedOrOracle) {
  const fs::path work = fs::temp_directory_path() / ("slide_test_driver_masks_" + std::to_string(::getpid()));
  fs::remove_all(work);
  simulator::ScenarioSpec spec;
  spec.world = "indoor";
  spec.robots = 1;
  spec.frames = 3;
  simulator::SensorOptions sensors;
  sensors.sensor = "rgbd";
  simulator::writeScenarioDataset(simulator::buildScenario(spec), sensors, (work / "data").string());
  const fs::path robot = work / "data" / "robot0";
  Published none = runLogOnly(work, robot, "");
  ASSERT_EQ(none.frames.size(), 3u) << driverLog(work);
  for (const auto& f : none.frames) {
    EXPECT_EQ(f.num_instances, 0);
    EXPECT_EQ(f.mask_size, 0);
  }
  Published emu = runLogOnly(work, robot, "--detections emulated");
  ASSERT_EQ(emu.frames.size(), 3u) << driverLog(work);
  int with_masks = 0;
  for (const auto& f : emu.frames) {
    with_masks += f.num_instances > 0;
    for (float c : f.instance_confidence) EXPECT_LT(c, 1.0f);  // a detector's score, not the oracle's 1.0
  }
  EXPECT_GT(with_masks, 0);
  Published oracle = runLogOnly(work, robot, "--detections oracle");
  ASSERT_EQ(oracle.frames.size(), 3u);
  for (const auto& f : oracle.frames)
    for (float c : f.instance_confidence) EXPECT_EQ(c, 1.0f);
  fs::remove_all(work);
}

namespace {
struct Failure {
  int exit_code = 0;
  std::vector<stream_status_t> statuses;
};

std::vector<stream_status_t> readStatuses(const fs::path& log) {
  std::vector<stream_status_t> out;
  lcm::LogFile f(log.string(), "r");
  if (!f.good()) return out;
  while (const lcm::LogEvent* ev = f.readNextEvent()) {
    stream_status_t m;
    if (ev->channel == "SENSOR_STATUS" && m.decode(ev->data, 0, ev->datalen) > 0) out.push_back(m);
  }
  return out;
}

// The driver with --no-publish --log on `dataset`; what its log's status channel says.
Failure runFailing(const fs::path& work, const std::string& dataset, const std::string& args) {
  const fs::path log = work / "failed.lcm";
  fs::remove(log);
  const std::string cmd = std::string(SLIDE_BINARY_DIR) + "/bin/slide-sensor-driver " + dataset +
                          " --rate 0 --no-progress --no-publish --log " + log.string() + " " + args + " > " +
                          (work / "driver.log").string() + " 2>&1";
  Failure f;
  f.exit_code = std::system(cmd.c_str());
  f.statuses = readStatuses(log);
  return f;
}
}  // namespace

TEST(SensorDriver, StopOnABadDatasetOrConfigPublishesFailedWithTheReason) {
  const fs::path work = fs::temp_directory_path() / ("slide_test_driver_failed_" + std::to_string(::getpid()));
  fs::remove_all(work);
  fs::create_directories(work);
  const std::string missing = (work / "no_such_robot").string();
  Failure bad = runFailing(work, missing, "");
  EXPECT_NE(bad.exit_code, 0);
  ASSERT_EQ(bad.statuses.size(), 1u) << driverLog(work);
  EXPECT_EQ(bad.statuses[0].state, stream_status_t::FAILED);
  EXPECT_NE(bad.statuses[0].reason.find(missing), std::string::npos) << bad.statuses[0].reason;
  EXPECT_EQ(bad.statuses[0].source, missing);

  writeSmallForest(work, 2);
  std::ofstream(work / "drv.yaml") << "sensor_driver:\n  rate: 1\n  max_gap: 2\n";
  Failure cfg = runFailing(work, (work / "data" / "robot0").string(), "--config " + (work / "drv.yaml").string());
  EXPECT_NE(cfg.exit_code, 0);
  ASSERT_EQ(cfg.statuses.size(), 1u) << driverLog(work);
  EXPECT_EQ(cfg.statuses[0].state, stream_status_t::FAILED);
  EXPECT_NE(cfg.statuses[0].reason.find("sensor_driver.max_gap (line 3): unknown key; did you mean 'max_gap_s'?"),
            std::string::npos)
      << cfg.statuses[0].reason;

  Failure good = runFailing(work, (work / "data" / "robot0").string(), "");  // control: a clean run ends FINISHED
  EXPECT_EQ(good.exit_code, 0) << driverLog(work);
  ASSERT_FALSE(good.statuses.empty());
  EXPECT_EQ(good.statuses.back().state, stream_status_t::FINISHED);
  EXPECT_EQ(good.statuses.back().reason, "");
  fs::remove_all(work);
}

TEST(SensorDriver, BadDatasetAtStartPublishesFailedOnTheBus) {
  if (!canRun()) GTEST_SKIP() << "needs root, unshare, ip and the LCM tools";
  const fs::path work = fs::temp_directory_path() / ("slide_test_driver_failed_bus_" + std::to_string(::getpid()));
  fs::remove_all(work);
  fs::create_directories(work / "empty_robot");
  const std::string url = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";
  std::ofstream(work / "run.sh") << "ip link set lo up\nip route add 224.0.0.0/4 dev lo\ncd " << work << "\n"
                                 << "lcm-logger -q -f --lcm-url='" << url << "' rec.lcm & L=$!\nsleep 1\n"
                                 << SLIDE_BINARY_DIR << "/bin/slide-sensor-driver " << (work / "empty_robot")
                                 << " --no-progress --lcm-url='" << url << "'\necho \"driver exit $?\"\n"
                                 << "sleep 0.5\nkill -INT $L; wait $L\n";
  std::system(("unshare -n bash " + (work / "run.sh").string() + " > " + (work / "run.log").string() + " 2>&1").c_str());
  std::ifstream in(work / "run.log");
  const std::string run_log((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(run_log.find("driver exit 1"), std::string::npos) << run_log;
  const std::vector<stream_status_t> st = readStatuses(work / "rec.lcm");
  ASSERT_EQ(st.size(), 1u) << run_log;
  EXPECT_EQ(st[0].state, stream_status_t::FAILED);
  EXPECT_NE(st[0].reason.find("empty_robot"), std::string::npos) << st[0].reason;
  fs::remove_all(work);
}
