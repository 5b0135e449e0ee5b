// slide-optimizer as a process on a real LCM bus inside a private network namespace
// (unshare -n; loopback up with a multicast route): bundles in, map/trajectory/status out,
// TUM trajectory written at exit. Needs root for the namespace (skipped otherwise).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <thread>

#include "scenario_messages.h"
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
}  // namespace

TEST(OptimizerDaemon, PublishesMapAndTrajectoryOverLcm) {
  if (!std::getenv("SLIDE_IN_NETNS")) {
    if (geteuid() != 0) GTEST_SKIP() << "needs root to create a network namespace (unshare -n)";
    const std::string cmd =
        "unshare -n sh -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo && SLIDE_IN_NETNS=1 exec " + self() +
        " --gtest_filter=OptimizerDaemon.PublishesMapAndTrajectoryOverLcm'";
    const int rc = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(rc));
    EXPECT_EQ(WEXITSTATUS(rc), 0) << "the test inside the namespace failed";
    return;
  }
  const auto dir = std::filesystem::temp_directory_path() / ("slide_daemon_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string bin = std::string(SLIDE_BINARY_DIR) + "/bin/slide-optimizer";
  const std::string journal = (dir / "optimizer.journal").string(), out = (dir / "tum").string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl(bin.c_str(), bin.c_str(), "--robot", "0", "--lcm-url", kUrl, "--journal", journal.c_str(), "--out-dir",
          out.c_str(), "--log-level", "warn", static_cast<char*>(nullptr));
    _exit(127);
  }

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
