// Runs slide-loop-closer in a private network namespace, feeds it two robots' maps over LCM and
// checks the published loop closure.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <sched.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>

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
