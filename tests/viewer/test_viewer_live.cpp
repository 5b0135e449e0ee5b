// slide-viewer on live buses, in a private network namespace (unshare -n; needs root): with only
// --robot 1 it hears robot 1's bus (README: udpm://239.255.76.67:7668), and with --team-url the
// team bus. What robot 1's daemons publish reaches a browser's WebSocket; garbage and absurd
// messages on the same channels are dropped and counted (GET /stats) and the viewer stays up.
// It publishes nothing: the buses carry only what the test sent.
#include <gtest/gtest.h>
#include <sched.h>

#include <lcm/lcm-cpp.hpp>
#include <set>

#include "viewer_log_fixture.h"
#include "viewer_process.h"

using namespace slide;
using namespace slide::viewer_test;

namespace {
const char* kRobot1Bus = "udpm://239.255.76.67:7668?ttl=0";
const char* kTeamBus = "udpm://239.255.76.90:7690?ttl=0";

struct Channels {
  std::set<std::string> seen;
  void on(const lcm::ReceiveBuffer*, const std::string& channel) { seen.insert(channel); }
};
}  // namespace

TEST(ViewerLive, RobotAndTeamBusesReachTheBrowserHostileInputIsCounted) {
  ASSERT_EQ(unshare(CLONE_NEWNET), 0) << "unshare(CLONE_NEWNET) failed (tests run as root)";
  ASSERT_EQ(std::system("ip link set lo up && ip route add 224.0.0.0/4 dev lo"), 0);
  const std::string dir = std::string(SLIDE_BINARY_DIR) + "/tests/viewer";
  const int port = freePort();
  ViewerProcess viewer({"--robot", "1", "--team-url", kTeamBus, "--port", std::to_string(port), "--period", "0.1"},
                       dir + "/live_viewer.log", port);
  ASSERT_TRUE(viewer.alive()) << "slide-viewer did not start: " << dir << "/live_viewer.log";
  const int browser = openSocket(port);
  ASSERT_GE(browser, 0);

  lcm::LCM bus(kRobot1Bus), team(kTeamBus);
  ASSERT_TRUE(bus.good() && team.good());
  Channels heard;
  bus.subscribe(".*", &Channels::on, &heard);
  team.subscribe(".*", &Channels::on, &heard);
  // Hostile first: random bytes, a truncated map, NaN poses; then the real thing.
  std::vector<std::uint8_t> junk(3000);
  for (std::size_t i = 0; i < junk.size(); ++i) junk[i] = static_cast<std::uint8_t>(i * 31 + 7);
  const auto map_bytes = msg::encodeLcm(mapMsg(1, {car(7, 3, 4), trunk(8, 6, -2)}));
  trajectory_t nan_traj = trajectoryMsg(1, 1, 4, 0, 0);
  nan_traj.poses[1].orientation[0] = NAN;
  std::string got;
  for (int round = 0; round < 10 && got.find("[8,71.0,1.0,6.0,-2.0,") == std::string::npos; ++round) {
    bus.publish("OBJECT_MAP", junk.data(), static_cast<unsigned>(junk.size()));
    bus.publish("OBJECT_MAP", map_bytes.data(), static_cast<unsigned>(map_bytes.size() / 2));
    bus.publish("TRAJECTORY", &nan_traj);
    team.publish("TEAM_HEARTBEAT", junk.data(), 40);
    const auto good_traj = trajectoryMsg(1, 1, 12, 0, 0);
    bus.publish("TRAJECTORY", &good_traj);
    bus.publish("OBJECT_MAP", map_bytes.data(), static_cast<unsigned>(map_bytes.size()));
    const auto hb = heartbeatMsg(2, round);
    team.publish("TEAM_HEARTBEAT", &hb);
    got += readAll(browser, 0.5);
  }
  EXPECT_NE(got.find("[7,10.0,0.0,3.0,4.0,"), std::string::npos) << "robot 1's car never reached the browser";
  EXPECT_NE(got.find("[8,71.0,1.0,6.0,-2.0,"), std::string::npos) << "robot 1's trunk never reached the browser";
  EXPECT_NE(got.find("\"linked\":[2]"), std::string::npos) << "the team link to robot 2 was not shown";
  const std::string stats = get(port, "/stats");
  EXPECT_NE(stats.find("OBJECT_MAP: "), std::string::npos) << stats;
  EXPECT_NE(stats.find("TRAJECTORY: "), std::string::npos) << stats;
  EXPECT_NE(stats.find("TEAM_HEARTBEAT: "), std::string::npos) << stats;
  // Only what the test published is on the buses: the viewer sent nothing.
  while (bus.handleTimeout(50) > 0 || team.handleTimeout(50) > 0) {
  }
  EXPECT_EQ(heard.seen, (std::set<std::string>{"OBJECT_MAP", "TRAJECTORY", "TEAM_HEARTBEAT"}));
  close(browser);
  EXPECT_TRUE(viewer.alive());
  EXPECT_EQ(viewer.stop(), 0);
}
