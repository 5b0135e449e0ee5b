// slide-peer-sync: wires the peer-sync engine (lib/team) to the robot bus and the team bus.
#include <spdlog/spdlog.h>

#include <lcm/lcm-cpp.hpp>

#include "app/app.h"
#include "app/clock.h"
#include "app/robot_bus.h"
#include "app/stop_signal.h"
#include "msg/inbox.h"
#include "msg/bus_wait.h"
#include "peer_sync_config.h"
#include "peer_sync_node.h"

using namespace slide;

int main(int argc, char** argv) {
  CLI::App app{"Peer-sync bookmark service: exchanges key-pose bundles and maps with teammates over the team bus, "
               "journals them, and delivers peers' bundles exactly once and in order on the robot bus."};
  app::CommonOptions common;
  app::addCommonOptions(app, common);
  std::string config_path = std::string(SLIDE_SOURCE_DIR) + "/config/peer_sync.yaml";
  app::RobotBusOptions bus;
  std::string state_dir, team_url, team_key_file;
  double run_for_s = 0;
  app.add_option("--config", config_path, "Peer-sync configuration (YAML; or a shared file with a peer_sync section)")
      ->capture_default_str();
  app::addRobotBusOptions(app, bus)->required()->description("This robot's id (must be in the config's team list)");
  app.get_option("--lcm-url")->description("Robot bus URL (default: config robot_url, else robot <id>'s own bus)");
  app.add_option("--robot-url", bus.url, "Same as --lcm-url");
  app.add_option("--state-dir", state_dir, "Folder for journal and counters (default: config state_dir/robot<id>; without one /var/lib/slide/peer-sync/robot<id> as root, else $XDG_STATE_HOME/slide/... or ~/.local/state/slide/...)");
  app.add_option("--team-url", team_url, "LCM URL of the team bus (default: config team_url)");
  app.add_option("--team-key-file", team_key_file,
                 "This robot's team key file: the keys it shares with each peer, mode 0600, made by slide-team-keys "
                 "(default: config team_key_file; {robot} stands for the id)");
  app.add_option("--run-for", run_for_s, "Exit after this many seconds (0: until SIGINT/SIGTERM)");
  return app::runApp(app, common, argc, argv, [&]() {
    // Either a peer-sync file, or a shared file with a `peer_sync:` section.
    const ConfigNode root = ConfigNode::load(config_path);
    const ConfigNode cfg = root.has("peer_sync") ? root.child("peer_sync") : root;
    const PeerSyncSetup setup = readPeerSyncSetup(cfg, bus, team_url, state_dir, team_key_file);
    const auto& ch = setup.channels;
    lcm::LCM robot_bus(setup.robot_url), team_bus(setup.team_url);
    if (!robot_bus.good()) throw std::runtime_error("cannot open robot bus " + setup.robot_url);
    if (!team_bus.good()) throw std::runtime_error("cannot open team bus " + setup.team_url);
    team::PeerSyncNode node(setup.sync, setup.state_dir, app::steadyMicros(), ch.team);
    // Raw subscriptions: the hardened decoders (cmake/lcm_gen_checked.cmake) run on bytes
    // already capped in size; a team frame's payload is decoded only after its MAC passed.
    msg::Inbox robot_inbox(robot_bus), team_inbox(team_bus, kMaxTeamFrameBytes);
    PeerSyncDaemon daemon(node, ch, setup.max_deliveries, msg::lcmPublisher(robot_bus), msg::lcmPublisher(team_bus),
                          {[&](const std::string& c, const std::string& why) { robot_inbox.countUndecodable(c, why); },
                           [&] { return msg::summaries({&robot_inbox, &team_inbox}); }});
    daemon.logStart(setup.state_dir);
    spdlog::info("robot {}: robot bus {}, team bus {}", bus.robot, setup.robot_url, setup.team_url);
    robot_inbox.subscribeBytes(ch.own_bundle,
                               [&](auto& c, auto* d, auto n) { daemon.onOwnBundle(c, d, n, app::steadyMicros()); });
    robot_inbox.subscribeBytes(ch.own_map,
                               [&](auto& c, auto* d, auto n) { daemon.onOwnMap(c, d, n, app::steadyMicros()); });
    for (const std::string& team_channel : {ch.team.heartbeat, ch.team.chunk, ch.team.ack})
      team_inbox.subscribeBytes(team_channel,
                                [&](auto& c, auto* d, auto n) { daemon.onTeam(c, d, n, app::steadyMicros()); });
    app::installStopHandlers();
    const team::Micros start = app::steadyMicros(), run_for = static_cast<team::Micros>(run_for_s * 1e6);
    team::Micros next_tick = start, next_stats = start + setup.stats_us;
    while (!app::stopRequested() && (run_for_s <= 0 || app::steadyMicros() - start < run_for)) {
      msg::handleAny({&robot_bus, &team_bus}, next_tick - app::steadyMicros());
      const team::Micros now = app::steadyMicros();
      if (now >= next_tick) {
        daemon.step(now);
        next_tick = now + setup.tick_us;
      }
      if (now >= next_stats) {
        daemon.logStats(now);
        next_stats = now + setup.stats_us;
      }
    }
    daemon.step(app::steadyMicros());  // the last sends and deliveries, and the final counts
    daemon.logStats(app::steadyMicros());
    node.persist();
    spdlog::info("robot {}: stopped", bus.robot);
    return 0;
  });
}
