#pragma once
// Which robot bus a daemon joins. Every daemon takes --robot N and --lcm-url URL; without a URL
// (on the command line or in its config) robot N's daemons meet on
// udpm://239.255.76.67:<7667+N>?ttl=0&recv_buf_size=4194304: one port per robot, so robots on one
// host do not see each other's raw data; ttl=0 keeps it on the host; the receive buffer holds a
// burst of a few 400 KB scans, which the kernel's 208 KB default loses (the kernel caps it at
// net.core.rmem_max and LCM warns when it does).
#include <CLI/CLI.hpp>
#include <string>

namespace slide::app {

constexpr int kRobotBusRecvBufBytes = 4194304;
std::string robotBusUrl(int robot);

struct RobotBusOptions {
  int robot = 0;
  std::string url;  // --lcm-url; empty: none given
  // --lcm-url if given, else `configured` (a config file's URL) if not empty, else robotBusUrl(robot).
  std::string resolve(const std::string& configured = "") const;
};

// Adds --robot and --lcm-url to `app`; returns the --robot option (to make it required, or to
// see whether it was given).
CLI::Option* addRobotBusOptions(CLI::App& app, RobotBusOptions& opts);

}  // namespace slide::app
