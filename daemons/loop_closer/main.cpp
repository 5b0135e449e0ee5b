// slide-loop-closer: own map, trajectory and peers' maps in; loop closures out. Place
// recognition runs here, in its own process, off the optimizer's path.
#include <lcm/lcm-cpp.hpp>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <map>

#include "app/app.h"
#include "app/clock.h"
#include "app/robot_bus.h"
#include "app/stop_signal.h"
#include "config/config.h"
#include "io/object_map_text.h"
#include "loop_closer_node.h"
#include "msg/convert.h"
#include "msg/inbox.h"
#include "msg/status_beacon.h"
#include "place/loop_closer_config.h"

using namespace slide;

namespace {
// --replay: the recording's maps and trajectory through the node in their order, polled every
// 100 ms of the recording's time (the daemon's loop); each found transform is logged by the
// node with its consensus outcome.
// With dump_dir: the last map of each robot (own and peers', each in its own frame) is written
// there as robot<N>.txt (label x y z sx sy sz), for ./slide match and recorded test cases.
int replayLog(const std::string& path, const place::LoopCloserParams& params, const LoopCloserChannels& ch,
              const std::string& dump_dir) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw std::runtime_error(path + ": cannot open the LCM log");
  long published = 0;
  LoopCloserNode node(params, ch, [&](const std::string&, const std::vector<uint8_t>&) { return ++published, true; });
  constexpr double kCatchUpS = 10.0;
  double t0 = -1, next_poll = 0, skipped_s = 0;
  long events = 0, undecodable = 0, maps = 0, own_maps = 0;
  std::map<int, ObjectMap> last;  // robot -> its last map in its own frame
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    const double t = ev->timestamp * 1e-6;
    if (t0 < 0) t0 = t, next_poll = t;
    // A gap in the recording (or a corrupt timestamp far ahead) is crossed with the last 10 s
    // of polls: every check falls due within its period (at most a few seconds) anyway.
    if (t - next_poll > kCatchUpS) skipped_s += t - kCatchUpS - next_poll, next_poll = t - kCatchUpS;
    for (; next_poll <= t; next_poll += 0.1) node.poll(next_poll);
    ++events;
    if (ev->channel == ch.own_map || ev->channel == ch.peer_maps) {
      object_map_t m;
      if (m.decode(ev->data, 0, ev->datalen) != ev->datalen) { ++undecodable; continue; }
      node.onMap(ev->channel, m, t);
      ++maps;
      if (!dump_dir.empty() && m.frame_robot == m.robot) {
        ObjectMap map;
        for (const object_t& o : m.objects)
          if (const Object obj = msg::fromLcm(o); obj.isFinite()) map.add(obj);
        last[m.robot] = std::move(map);
      }
      own_maps += m.robot == params.robot;
    } else if (ev->channel == ch.trajectory) {
      trajectory_t m;
      if (m.decode(ev->data, 0, ev->datalen) != ev->datalen) { ++undecodable; continue; }
      node.onTrajectory(m);
    }
  }
  node.poll(next_poll);
  if (own_maps == 0)
    spdlog::warn("{}: no map of robot {} on '{}' or '{}' (was the own map recorded? is --robot the recording's?)", path,
                 params.robot, ch.own_map, ch.peer_maps);
  if (skipped_s > 0) spdlog::warn("{}: {:.0f} s of gaps between recorded events were not polled", path, skipped_s);
  spdlog::info("{}: {} events over {:.1f} s, {} maps, {} undecodable; {} closures would have been published", path, events,
               t0 < 0 ? 0.0 : next_poll - t0, maps, undecodable, published);
  if (!dump_dir.empty()) {
    std::filesystem::create_directories(dump_dir);
    const ClassTable classes = ClassTable::loadDefault();
    for (const auto& [robot, map] : last) {
      const std::string file = dump_dir + "/robot" + std::to_string(robot) + ".txt";
      io::writeObjectMapText(file, map, classes);
      spdlog::info("robot {}'s last map ({} objects): {}", robot, map.size(), file);
    }
  }
  return 0;
}
}  // namespace

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
  std::string replay;
  app.add_option("--replay", replay,
                 "Instead of the bus: run on a recorded robot bus (an lcm-logger file with the own map, the peers'\n"
                 "maps and the trajectory) as fast as it goes, on the recording's clock, printing every check's\n"
                 "outcome and publishing nothing")
      ->check(CLI::ExistingFile);
  std::string dump_dir;
  app.add_option("--dump-maps", dump_dir,
                 "With --replay: write each robot's last map of the recording (own and peers', each in its own\n"
                 "frame) to DIR/robot<N>.txt (label x y z sx sy sz), the input of slide-match")
      ->needs("--replay");
  return app::runApp(app, common, argc, argv, [&]() {
    const ConfigNode cfg = ConfigNode::load(config_path);
    place::LoopCloserParams params = place::loadLoopCloserParams(cfg);
    LoopCloserChannels ch;
    const std::string cfg_url = readLoopCloserBus(cfg, ch);
    cfg.rejectUnknownKeys();
    if (robot_opt->count()) params.robot = bus.robot;
    else bus.robot = params.robot;
    if (!method.empty()) params.method = place::parsePlaceMethod(method);
    if (!replay.empty()) return replayLog(replay, params, ch, dump_dir);
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
