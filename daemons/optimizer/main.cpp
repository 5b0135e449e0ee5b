// slide-optimizer: the back-end daemon of one robot. Key-pose bundles (own and peers'),
// loop closures and inter-robot transforms in; object map, trajectories and status out.
#include <spdlog/spdlog.h>

#include <lcm/lcm-cpp.hpp>

#include "app/app.h"
#include "app/robot_bus.h"
#include "app/stop_signal.h"
#include "backend/backend_config.h"
#include "msg/inbox.h"
#include "optimizer_node.h"

using namespace slide;

int main(int argc, char** argv) {
  CLI::App app{"Back-end optimizer: keeps the robot's factor graph of key poses and object landmarks "
               "optimized, merges peers once their transform is known, publishes map and trajectories"};
  app::CommonOptions common;
  app::RobotBusOptions bus;
  std::string config_path = std::string(SLIDE_SOURCE_DIR) + "/config/backend.yaml";
  std::string classes_path = std::string(SLIDE_SOURCE_DIR) + "/config/classes.yaml";
  std::string journal_path, out_dir;
  int publish_every = 1;
  double write_period = 10, settle_after = 3;
  bool inline_solves = false;
  OptimizerChannels ch;
  app::addRobotBusOptions(app, bus);
  app.add_option("--config", config_path, "back-end parameters (YAML)")->capture_default_str();
  app.add_option("--classes", classes_path, "class table (YAML)")->capture_default_str();
  app.add_option("--journal", journal_path,
                 "journal of every accepted input (checksummed records): replayed at start, appended while running");
  app.add_option("--out-dir", out_dir, "write TUM trajectories and the object map here: periodically, on SIGUSR1 and at exit");
  app.add_option("--write-period", write_period, "seconds between writes of the outputs (0: only on SIGUSR1 and at exit)")
      ->capture_default_str();
  app.add_option("--settle-after", settle_after,
                 "seconds without input after which the estimate is solved to convergence once (0: never)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--inline-solves", inline_solves,
               "run full solves inside the updates that ask for them (an update then waits for one: seconds on long "
               "missions); by default they run on a worker thread on a snapshot of the graph and the update path "
               "never waits for one");
  app.add_option("--publish-every", publish_every, "publish map and trajectories every N updates (and on full solves)")
      ->capture_default_str();
  app.add_option("--bundle-channel", ch.bundle)->capture_default_str();
  app.add_option("--peer-bundle-channel", ch.peer_bundle)->capture_default_str();
  app.add_option("--loop-closure-channel", ch.loop_closure)->capture_default_str();
  app.add_option("--object-map-channel", ch.object_map)->capture_default_str();
  app.add_option("--own-map-channel", ch.own_map)->capture_default_str();
  app.add_option("--trajectory-channel", ch.trajectory)->capture_default_str();
  app.add_option("--status-channel", ch.status)->capture_default_str();
  app::addCommonOptions(app, common);
  return app::runApp(app, common, argc, argv, [&]() {
    const std::string url = bus.resolve();
    backend::BackendConfig cfg = backend::loadBackendConfig(config_path);
    cfg.background_solves = !inline_solves;
    const ClassTable classes = ClassTable::load(classes_path);
    lcm::LCM lcm(url);
    if (!lcm.good()) throw std::runtime_error("cannot open LCM at " + url);
    OptimizerNode node(cfg, classes, bus.robot, ch, msg::lcmPublisher(lcm), publish_every);
    node.setOutputs(out_dir, write_period);
    node.setSettle(settle_after);
    node.optimizer().setStopFlag(app::stopFlag());  // a stop aborts a solve running inside an update
    app::installStopHandlers();
    app::installWriteHandler();
    if (!journal_path.empty()) {
      node.openJournal(journal_path);
      node.publishAll();
    }
    msg::Inbox inbox(lcm);
    for (const std::string& input : {ch.bundle, ch.peer_bundle, ch.loop_closure})
      inbox.subscribeBytes(input, [&](auto& c, auto* d, auto n) { node.handle(c, d, static_cast<int>(n)); });
    node.setBusDrops([&inbox]() { return inbox.dropped(); });
    spdlog::info("robot {} optimizer on {} (in: {}, {}, {}; out: {}, {}, {})", bus.robot, url, ch.bundle, ch.peer_bundle,
                 ch.loop_closure, ch.object_map, ch.trajectory, ch.status);
    while (!app::stopRequested()) {
      if (lcm.handleTimeout(100) < 0 && !app::stopRequested()) throw std::runtime_error("LCM receive failed on " + url);
      node.poll();
      if (app::takeWriteRequest()) node.writeOutputs();
    }
    node.stop();
    const backend::Optimizer& o = node.optimizer();
    spdlog::info("stopping: {} key poses, {} landmarks, {} peers merged, {} inputs rejected, {} undecodable, "
                 "dropped on the bus: {}", o.numKeyPoses(), o.numLandmarks(), o.numPeersMerged(), o.rejected(),
                 node.decodeErrors(), inbox.dropped() ? inbox.summary() : "none");
    return 0;
  });
}
