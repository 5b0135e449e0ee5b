// slide-loop-closer: own map, trajectory and peers' maps in; loop closures out. Place
// recognition runs here, in its own process, off the optimizer's path.
#include <lcm/lcm-cpp.hpp>
#include <spdlog/spdlog.h>

#include "app/app.h"
#include "app/clock.h"
#include "app/robot_bus.h"
#include "app/stop_signal.h"
#include "config/config.h"
#include "loop_closer_node.h"
#include "msg/inbox.h"
#include "msg/status_beacon.h"
#include "place/loop_closer_config.h"

using namespace slide;

int main(int argc, char** argv) {
  CLI::App app{"Loop closer: intra-robot (by proximity, against the robot's older objects) and inter-robot (own map\n"
               "against each peer's map, staggered, re-checked when maps change) place recognition; publishes\n"
               "slide.loop_closure_t after a consensus filter over repeated results.",
               "slide-loop-closer"};
  app::CommonOptions common;
  app::addCommonOptions(app, common);
  app::RobotBusOptions bus;
  std::string config_path = std::string(SLIDE_SOURCE_DIR) + "/config/loop_closer.yaml", method;
  app.add_option("--config", config_path, "Loop-closer configuration")->capture_default_str();
  CLI::Option* robot_opt = app::addRobotBusOptions(app, bus)->description("Own robot id (overrides the config's)");
  app.get_option("--lcm-url")->description("Robot bus URL (overrides the config's; default the robot's own bus)");
  app.add_option("--method", method, "slidegraph or slidematch (overrides the config)")
      ->check(CLI::IsMember({"slidegraph", "slidematch"}));
  return app::runApp(app, common, argc, argv, [&]() {
    const ConfigNode cfg = ConfigNode::load(config_path);
    place::LoopCloserParams params = place::loadLoopCloserParams(cfg);
    LoopCloserChannels ch;
    const std::string cfg_url = readLoopCloserBus(cfg, ch);
    cfg.rejectUnknownKeys();
    if (robot_opt->count()) params.robot = bus.robot;
    else bus.robot = params.robot;
    if (!method.empty()) params.method = place::parsePlaceMethod(method);
    const std::string url = bus.resolve(cfg_url);

    lcm::LCM lcm(url);
    if (!lcm.good()) throw std::runtime_error("cannot open LCM at '" + url + "'");
    LoopCloserNode node(params, ch, msg::lcmPublisher(lcm));
    msg::Inbox inbox(lcm);
    auto on_map = [&](const std::string& c, const object_map_t& m) { node.onMap(c, m, app::steadySeconds()); };
    inbox.subscribe<object_map_t>(ch.own_map, on_map);
    if (ch.peer_maps != ch.own_map) inbox.subscribe<object_map_t>(ch.peer_maps, on_map);
    inbox.subscribe<trajectory_t>(ch.trajectory, [&](const std::string&, const trajectory_t& m) { node.onTrajectory(m); });
    app::installStopHandlers();
    spdlog::info("robot {}: {} on {}, maps '{}'/'{}', trajectory '{}', out '{}'", params.robot,
                 place::methodName(params.method), url, ch.own_map, ch.peer_maps, ch.trajectory, ch.loop_closures);
    msg::StatusBeacon status(lcm, ch.status, params.robot, "loop_closer");
    auto counts = [&](bool now) { status.tick(node.published(), inbox.dropped(), node.droppedInputs(), now); };
    while (!app::stopRequested()) {
      counts(false);
      if (lcm.handleTimeout(100) < 0) {
        if (app::stopRequested()) break;  // select() interrupted by the stop signal
        throw std::runtime_error("LCM receive failed on '" + url + "'");
      }
      node.poll(app::steadySeconds());
    }
    counts(true);
    spdlog::info("stopping; dropped messages: {}; dropped map objects: {}; oversized maps dropped: {}; checks over "
                 "budget: {}",
                 inbox.dropped() ? inbox.summary() : "none", node.droppedObjects(),
                 node.closer().counts().oversized_maps, node.closer().counts().budget_exceeded);
    return 0;
  });
}
