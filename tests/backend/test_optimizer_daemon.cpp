// slide-optimizer as a process on a real LCM bus inside a private network namespace
// (unshare -n; loopback up with a multicast route): bundles in, map/trajectory/status out,
// TUM trajectory written at exit; on a long mission, SIGTERM still writes the outputs within
// 2 s and SIGKILL leaves the last periodic output whole. Needs root for the namespace
// (skipped otherwise).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <random>
#include <thread>

#include "io/tum_trajectory.h"
#include "io/object_map_text.h"
#include "scenario_messages.h"
#include "team/journal.h"
#include "slide/object_map_t.hpp"
#include "slide/optimizer_status_t.hpp"
#include "slide/trajectory_t.hpp"

using namespace slide;

namespace {
const char* kUrl = "udpm://239.255.76.67:7690?ttl=0";

struct Outputs {
  object_map_t map;
  trajectory_t trajectory;
  int maps = 0, trajectories = 0, statuses = 0;
  void onMap(const lcm::ReceiveBuffer*, const std::string&, const object_map_t* m) { map = *m, ++maps; }
  void onTrajectory(const lcm::ReceiveBuffer*, const std::string&, const trajectory_t* m) { trajectory = *m, ++trajectories; }
  void onStatus(const lcm::ReceiveBuffer*, const std::string&, const optimizer_status_t*) { ++statuses; }
};

std::string self() { return std::filesystem::read_symlink("/proc/self/exe").string(); }

// Outside a namespace: runs the current test again inside a new one and returns true (the
// caller returns). Inside: returns false and the test runs.
bool rerunInNamespace() {
  if (std::getenv("SLIDE_IN_NETNS")) return false;
  const auto* t = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string cmd = "unshare -n sh -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo && SLIDE_IN_NETNS=1 exec " +
                          self() + " --gtest_filter=" + t->test_suite_name() + "." + t->name() + "'";
  const int rc = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 0) << "the test inside the namespace failed";
  return true;
}

// Skipped without root (the namespace needs it).
#define RUN_IN_NAMESPACE()                                                     \
  do {                                                                         \
    if (!std::getenv("SLIDE_IN_NETNS") && geteuid() != 0)                      \
      GTEST_SKIP() << "needs root to create a network namespace (unshare -n)"; \
    if (rerunInNamespace()) return;                                            \
  } while (0)

pid_t startOptimizer(const std::vector<std::string>& args) {
  const std::string bin = std::string(SLIDE_BINARY_DIR) + "/bin/slide-optimizer";
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv{const_cast<char*>(bin.c_str())};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(bin.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

// A long mission's own bundles (forest tiles chained) as LCM bytes.
std::vector<std::vector<uint8_t>> longMission(int keyposes) {
  const graph_scenario::GraphScenario s = graph_scenario::makeForestChainScenario(keyposes);
  std::vector<std::vector<uint8_t>> out;
  for (const auto& b : s.robots[0].bundles) out.push_back(slide::testing::encodeMsg(msg::toLcm(b)));
  return out;
}

// A journal of the first `count` of them, as the daemon writes it (record type 1: own bundle).
void writeJournal(const std::string& path, const std::vector<std::vector<uint8_t>>& bundles, std::size_t count) {
  std::filesystem::remove(path);
  std::vector<team::JournalRecord> none;
  team::Journal journal(path, &none);
  for (std::size_t i = 0; i < count; ++i) journal.append(1, bundles[i]);
}

// Waits for the daemon's first object map (published once its journal is replayed).
bool waitForMap(lcm::LCM& lcm, Outputs& got, int seconds) {
  const auto start = std::chrono::steady_clock::now();
  while (got.maps == 0 && std::chrono::steady_clock::now() - start < std::chrono::seconds(seconds)) lcm.handleTimeout(100);
  return got.maps > 0;
}

// A fresh temporary folder of this test process.
std::filesystem::path freshDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Starts the daemon on `journal` with outputs in `out`, written every `period` seconds; returns
// its pid once it has published its replayed map on `lcm` (-1 if it never did).
pid_t startReplayed(const std::string& journal, const std::string& out, const std::string& period, lcm::LCM& lcm) {
  Outputs got;
  lcm::Subscription* sub = lcm.subscribe("OBJECT_MAP", &Outputs::onMap, &got);
  const pid_t pid = startOptimizer({"--robot", "0", "--lcm-url", kUrl, "--journal", journal, "--out-dir", out,
                                    "--write-period", period, "--log-level", "warn"});
  const bool ready = pid > 0 && waitForMap(lcm, got, 120);
  lcm.unsubscribe(sub);
  if (ready) return pid;
  if (pid > 0) kill(pid, SIGKILL), waitpid(pid, nullptr, 0);
  return -1;
}

bool waitExit(pid_t pid, int seconds, int* status) {
  const auto start = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - start < std::chrono::seconds(seconds)) {
    if (waitpid(pid, status, WNOHANG) == pid) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid, SIGKILL);
  waitpid(pid, status, 0);
  return false;
}
}  // namespace

TEST(OptimizerDaemon, PublishesMapAndTrajectoryOverLcm) {
  RUN_IN_NAMESPACE();
  const auto dir = std::filesystem::temp_directory_path() / ("slide_daemon_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string journal = (dir / "optimizer.journal").string(), out = (dir / "tum").string();
  const pid_t pid = startOptimizer({"--robot", "0", "--lcm-url", kUrl, "--journal", journal, "--out-dir", out,
                                    "--log-level", "warn"});
  ASSERT_GE(pid, 0);

  lcm::LCM lcm(kUrl);
  ASSERT_TRUE(lcm.good());
  Outputs got;
  lcm.subscribe("OBJECT_MAP", &Outputs::onMap, &got);
  lcm.subscribe("TRAJECTORY", &Outputs::onTrajectory, &got);
  lcm.subscribe("OPTIMIZER_STATUS", &Outputs::onStatus, &got);
  std::vector<slide::testing::RawMessage> own;
  for (const auto& m : slide::testing::twoRobotMessages())
    if (m.channel == "KEYPOSE_BUNDLE" && own.size() < 40) own.push_back(m);

  // Resend the first bundle until the daemon answers (repeats are rejected as duplicates).
  const auto start = std::chrono::steady_clock::now();
  while (got.statuses == 0 && std::chrono::steady_clock::now() - start < std::chrono::seconds(15)) {
    lcm.publish("KEYPOSE_BUNDLE", own[0].bytes.data(), static_cast<unsigned>(own[0].bytes.size()));
    lcm.handleTimeout(200);
  }
  ASSERT_GT(got.statuses, 0) << "no OPTIMIZER_STATUS from the daemon";
  for (std::size_t i = 1; i < own.size(); ++i) {
    lcm.publish("KEYPOSE_BUNDLE", own[i].bytes.data(), static_cast<unsigned>(own[i].bytes.size()));
    lcm.handleTimeout(5);
  }
  const auto wait_start = std::chrono::steady_clock::now();
  while (got.trajectory.num_poses < static_cast<int>(own.size()) &&
         std::chrono::steady_clock::now() - wait_start < std::chrono::seconds(15))
    lcm.handleTimeout(100);

  EXPECT_EQ(got.trajectory.num_poses, static_cast<int>(own.size()));
  EXPECT_EQ(got.trajectory.robot, 0);
  EXPECT_EQ(got.trajectory.frame_robot, 0);
  EXPECT_GT(got.maps, 0);
  EXPECT_GT(got.map.num_objects, 10);
  for (const auto& o : got.map.objects) EXPECT_GE(o.num_observations, 3);

  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  std::ifstream tum(out + "/trajectory_robot0.txt");
  ASSERT_TRUE(tum.good());
  int lines = 0;
  for (std::string line; std::getline(tum, line);) lines += !line.empty() && line[0] != '#';
  EXPECT_EQ(lines, static_cast<int>(own.size()));
  EXPECT_TRUE(std::filesystem::exists(journal));
  std::filesystem::remove_all(dir);
}

// 2000 key poses: a full solve to convergence takes several seconds here, and full solves run
// inside the replay's updates; asked to stop, the daemon aborts them and must not wait.
TEST(OptimizerDaemon, StopDuringALongMissionWritesTheOutputsWithinTwoSeconds) {
  RUN_IN_NAMESPACE();
  const auto dir = freshDir("slide_daemon_stop");
  const std::string journal = (dir / "optimizer.journal").string(), out = (dir / "out").string();
  writeJournal(journal, longMission(2000), 2000);
  lcm::LCM lcm(kUrl);
  ASSERT_TRUE(lcm.good());
  const pid_t pid = startReplayed(journal, out, "0", lcm);
  ASSERT_GT(pid, 0) << "the daemon never published its replayed map";
  const std::string tum = out + "/trajectory_robot0.txt";
  ASSERT_FALSE(std::filesystem::exists(tum));
  const auto t0 = std::chrono::steady_clock::now();
  kill(pid, SIGTERM);
  while (!std::filesystem::exists(tum) && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(30))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LE(seconds, 2.0) << "outputs written " << seconds << " s after SIGTERM";
  int status = 0;
  EXPECT_TRUE(waitExit(pid, 10, &status)) << "still running 10 s after SIGTERM";
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(io::readTum(tum).size(), 2000u);
  EXPECT_GT(io::readObjectMapText(out + "/map_robot0.txt", ClassTable::loadDefault(), io::MissingSize::Zero).map.size(),
            1000u);
  std::filesystem::remove_all(dir);
}

// Bundles keep coming, outputs are written every 20 ms; killed at random instants, the daemon
// leaves files that read whole (every key pose of some moment, never a cut line).
TEST(OptimizerDaemon, SigkillLeavesTheLastPeriodicOutputWhole) {
  RUN_IN_NAMESPACE();
  const auto dir = freshDir("slide_daemon_kill");
  const std::vector<std::vector<uint8_t>> bundles = longMission(1400);
  std::mt19937 rng(5);
  for (int round = 0; round < 3; ++round) {
    const std::string journal = (dir / "optimizer.journal").string(), out = (dir / "out").string();
    std::filesystem::remove_all(out);
    writeJournal(journal, bundles, 1000);
    lcm::LCM lcm(kUrl);
    ASSERT_TRUE(lcm.good());
    const pid_t pid = startReplayed(journal, out, "0.02", lcm);
    ASSERT_GT(pid, 0) << "the daemon never published its replayed map";
    const auto until = std::chrono::steady_clock::now() +
                       std::chrono::milliseconds(std::uniform_int_distribution<int>(300, 900)(rng));
    for (std::size_t i = 1000; i < bundles.size() && std::chrono::steady_clock::now() < until; ++i) {
      lcm.publish("KEYPOSE_BUNDLE", bundles[i].data(), static_cast<unsigned>(bundles[i].size()));
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    const std::string tum = out + "/trajectory_robot0.txt";
    ASSERT_TRUE(std::filesystem::exists(tum)) << "no periodic output in round " << round;
    const std::size_t poses = io::readTum(tum).size();  // throws on a cut line
    EXPECT_GE(poses, 1000u);
    EXPECT_LE(poses, bundles.size());
    EXPECT_GT(
        io::readObjectMapText(out + "/map_robot0.txt", ClassTable::loadDefault(), io::MissingSize::Zero).map.size(),
        500u);
  }
  std::filesystem::remove_all(dir);
}
