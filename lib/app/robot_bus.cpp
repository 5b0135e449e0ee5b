#include "app/robot_bus.h"

namespace slide::app {

std::string robotBusUrl(int robot) {
  return "udpm://239.255.76.67:" + std::to_string(7667 + robot) + "?ttl=0&recv_buf_size=" +
         std::to_string(kRobotBusRecvBufBytes);
}

std::string RobotBusOptions::resolve(const std::string& configured) const {
  if (!url.empty()) return url;
  if (!configured.empty()) return configured;
  return robotBusUrl(robot);
}

CLI::Option* addRobotBusOptions(CLI::App& app, RobotBusOptions& opts) {
  auto* robot = app.add_option("--robot", opts.robot, "This robot's id (stamped into messages; picks the robot bus)")
                    ->capture_default_str();
  app.add_option("--lcm-url", opts.url,
                 "Robot bus URL (default udpm://239.255.76.67:<7667+robot>?ttl=0&recv_buf_size=" +
                     std::to_string(kRobotBusRecvBufBytes) + ")");
  return robot;
}

}  // namespace slide::app
