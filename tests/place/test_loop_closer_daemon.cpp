// Runs slide-loop-closer in a private network namespace, feeds it two robots' maps over LCM and
// checks the published loop closure.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <sched.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "io/object_map_text.h"
#include "objects/class_table.h"
#include "slide/loop_closure_t.hpp"
#include "slide/object_map_t.hpp"
#include "two_robot_maps.h"

using namespace slide;

namespace {
const char* kUrl = "udpm://239.255.76.123:7723?ttl=0";

bool privateNetwork() {
  if (unshare(CLONE_NEWNET) != 0 && unshare(CLONE_NEWUSER | CLONE_NEWNET) != 0) return false;
  return std::system("ip link set lo up && ip route add 224.0.0.0/4 dev lo") == 0;
}

struct Collector {
  std::vector<loop_closure_t> got;
  void on(const lcm::ReceiveBuffer*, const std::string&, const loop_closure_t* m) { got.push_back(*m); }
};
}  // namespace

TEST(LoopCloserDaemon, PublishesTheTransformBetweenTwoRobotsMaps) {
  if (!privateNetwork()) GTEST_SKIP() << "cannot create a private network namespace (needs root or user namespaces)";
  const std::string config = ::testing::TempDir() + "loop_closer_test.yaml";
  {
    std::ofstream f(config);
    f << "robot: 0\nplace_config: " << SLIDE_SOURCE_DIR << "/config/place.yaml\n"
      << "lcm:\n  url: \"" << kUrl << "\"\ninter_robot:\n  period_s: 0.5\n  stagger_s: 0.0\n";
  }
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string bin = std::string(SLIDE_BINARY_DIR) + "/bin/slide-loop-closer";
    execl(bin.c_str(), bin.c_str(), "--config", config.c_str(), "--log-level", "warn", static_cast<char*>(nullptr));
    _exit(127);
  }
  lcm::LCM lcm(kUrl);
  ASSERT_TRUE(lcm.good());
  Collector c;
  lcm.subscribe("LOOP_CLOSURE", &Collector::on, &c);

  const auto [own, peer] = slide::testing::twoRobotViews(poseFromXyzYaw(-15, 22, 0.5, -2.0));
  const object_map_t own_msg = slide::testing::mapMsg(0, own), peer_msg = slide::testing::mapMsg(1, peer);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (c.got.empty() && std::chrono::steady_clock::now() < deadline) {
    lcm.publish("OWN_MAP", &own_msg);  // repeated: the daemon may still be starting
    lcm.publish("PEER_MAP", &peer_msg);
    lcm.handleTimeout(300);
  }
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "daemon exit status " << status;
  ASSERT_FALSE(c.got.empty()) << "no loop closure within 10 s";
  const loop_closure_t& lc = c.got.front();
  EXPECT_EQ(lc.robot_a, 0);
  EXPECT_EQ(lc.robot_b, 1);
  EXPECT_EQ(lc.method, loop_closure_t::SLIDEGRAPH);
  EXPECT_NEAR(lc.x, -15, 1e-3);
  EXPECT_NEAR(lc.y, 22, 1e-3);
  EXPECT_NEAR(lc.z, 0.5, 1e-3);
  EXPECT_NEAR(lc.yaw, -2.0, 1e-4);
  ASSERT_EQ(lc.num_inliers, 70);
  for (int i = 0; i < lc.num_inliers; ++i) EXPECT_EQ(lc.inliers_b[i], lc.inliers_a[i] + 100);
}

// --replay: a recorded robot bus (an lcm-logger file) through the loop closer on the recording's
// clock: the two maps, recorded again and again over 12 s, give the transform (printed with its
// consensus outcome), nothing is sent; a timestamp far ahead is crossed, not polled through;
// a missing file is refused by name.
TEST(LoopCloserDaemon, ReplaysARecordedBus) {
  const std::string log_path = ::testing::TempDir() + "loop_closer_replay.lcmlog";
  const auto [own, peer] = slide::testing::twoRobotViews(poseFromXyzYaw(-15, 22, 0.5, -2.0));
  object_map_t own_msg = slide::testing::mapMsg(0, own), peer_msg = slide::testing::mapMsg(1, peer);
  {
    lcm::LogFile log(log_path, "w");
    ASSERT_TRUE(log.good());
    std::vector<uint8_t> buf;
    auto write = [&](const std::string& channel, const object_map_t& m, int64_t utime) {
      buf.resize(m.getEncodedSize());
      m.encode(buf.data(), 0, static_cast<int>(buf.size()));
      lcm::LogEvent ev;
      ev.timestamp = utime;
      ev.channel = channel;
      ev.datalen = static_cast<int32_t>(buf.size());
      ev.data = buf.data();
      ASSERT_EQ(log.writeEvent(&ev), 0);
    };
    for (int k = 0; k < 12; ++k) {
      write("OWN_MAP", own_msg, 1'700'000'000'000'000 + k * 1'000'000LL);
      write("PEER_MAP", peer_msg, 1'700'000'000'000'000 + k * 1'000'000LL + 1000);
    }
    write("PEER_MAP", peer_msg, INT64_MAX / 2);  // a corrupt timestamp far ahead: no hang

  }
  const std::string bin = std::string(SLIDE_BINARY_DIR) + "/bin/slide-loop-closer";
  const std::string out = ::testing::TempDir() + "loop_closer_replay.txt";
  ASSERT_EQ(std::system((bin + " --robot 0 --replay " + log_path + " > " + out + " 2>&1").c_str()), 0);
  std::ifstream f(out);
  const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("robot 0 <- robot 1: accepted (70 inliers"), std::string::npos) << text;
  EXPECT_NE(text.find("25 maps"), std::string::npos) << text;
  EXPECT_NE(text.find("were not polled"), std::string::npos) << text;
  // --dump-maps: each robot's last map, as slide-match reads it.
  const std::string dump = ::testing::TempDir() + "loop_closer_replay_maps";
  std::filesystem::remove_all(dump);
  ASSERT_EQ(std::system((bin + " --robot 0 --replay " + log_path + " --dump-maps " + dump + " > " + out + " 2>&1").c_str()), 0);
  for (const auto& [robot, map] : {std::pair{0, &own}, std::pair{1, &peer}}) {
    const io::ObjectMapText read =
        io::readObjectMapText(dump + "/robot" + std::to_string(robot) + ".txt", ClassTable::loadDefault(), io::MissingSize::Zero);
    EXPECT_EQ(read.map.size(), map->size()) << robot;
  }
  EXPECT_NE(std::system((bin + " --robot 0 --replay /nonexistent/bus.lcmlog > " + out + " 2>&1").c_str()), 0);
  std::ifstream g(out);
  const std::string refused((std::istreambuf_iterator<char>(g)), std::istreambuf_iterator<char>());
  EXPECT_NE(refused.find("/nonexistent/bus.lcmlog"), std::string::npos) << refused;
}
