// lib/app: the robot bus every daemon joins for --robot N, and the clocks.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>

#include "app/clock.h"
#include "app/robot_bus.h"

using namespace slide;

namespace {
// Parses `args` (after the program name) into a fresh app with the robot-bus options.
app::RobotBusOptions parsed(std::vector<std::string> args) {
  CLI::App app;
  app::RobotBusOptions opts;
  app::addRobotBusOptions(app, opts);
  std::reverse(args.begin(), args.end());  // CLI11 takes the arguments reversed
  app.parse(args);
  return opts;
}
}  // namespace

TEST(RobotBus, RobotNIsOnPort7667PlusNOnTheHostOnly) {
  EXPECT_EQ(app::robotBusUrl(0), "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304");
  EXPECT_EQ(app::robotBusUrl(2), "udpm://239.255.76.67:7669?ttl=0&recv_buf_size=4194304");
  EXPECT_EQ(app::robotBusUrl(11), "udpm://239.255.76.67:7678?ttl=0&recv_buf_size=4194304");
}

TEST(RobotBus, RobotOptionAlonePicksTheRobotsBus) {
  EXPECT_EQ(parsed({"--robot", "2"}).resolve(), "udpm://239.255.76.67:7669?ttl=0&recv_buf_size=4194304");
  // A config's URL serves when the command line names none; --lcm-url wins over both.
  EXPECT_EQ(parsed({"--robot", "2"}).resolve("udpm://239.255.76.67:7700?ttl=0"), "udpm://239.255.76.67:7700?ttl=0");
  EXPECT_EQ(parsed({"--robot", "2", "--lcm-url", "udpm://239.255.76.67:7701?ttl=0"}).resolve("udpm://x:1"),
            "udpm://239.255.76.67:7701?ttl=0");
  EXPECT_EQ(parsed({}).resolve(), app::robotBusUrl(0));
}

TEST(Clock, WallMicrosIsUnixTimeAndSteadyClocksAgree) {
  const auto unix_us = std::chrono::duration_cast<std::chrono::microseconds>(
                           std::chrono::system_clock::now().time_since_epoch()).count();
  EXPECT_NEAR(static_cast<double>(app::wallMicros()), static_cast<double>(unix_us), 1e6);
  const double s = app::steadySeconds();
  const std::int64_t us = app::steadyMicros();
  EXPECT_NEAR(static_cast<double>(us) * 1e-6, s, 1.0);
  EXPECT_LE(s, app::steadySeconds());
}
