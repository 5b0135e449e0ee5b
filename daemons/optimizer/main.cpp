// slide-optimizer: the back-end daemon of one robot. Key-pose bundles (own and peers'),
// loop closures and inter-robot transforms in; object map, trajectories and status out.
#include <spdlog/spdlog.h>

#include <atomic>
#include <csignal>
#include <lcm/lcm-cpp.hpp>

#include "app/app.h"
#include "backend/backend_config.h"
#include "msg/inbox.h"
#include "optimizer_node.h"

using namespace slide;

namespace {
volatile std::sig_atomic_t g_stop = 0;
std::atomic<bool> g_abort_solves{false};  // lock-free: set from the signal handler
volatile std::sig_atomic_t g_write = 0;

struct Receiver {
  OptimizerNode* node;
  void onMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    node->handle(channel, rbuf->data, static_cast<int>(rbuf->data_size));
  }
};
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Back-end optimizer: keeps the robot's factor graph of key poses and object landmarks "
               "optimized, merges peers once their transform is known, publishes map and trajectories"};
  CommonOptions common;
  int robot = 0;
  std::string url, config_path = std::string(SLIDE_SOURCE_DIR) + "/config/backend.yaml";
  std::string classes_path = std::string(SLIDE_SOURCE_DIR) + "/config/classes.yaml";
  std::string journal_path, out_dir;
  int publish_every = 1;
  double write_period = 10;
  bool background_solves = false;
  OptimizerChannels ch;
  app.add_option("--robot", robot, "this robot's id")->capture_default_str();
  app.add_option("--lcm-url", url, "robot bus (default udpm://239.255.76.67:<7667+robot>?ttl=0&recv_buf_size=4194304)");
  app.add_option("--config", config_path, "back-end parameters (YAML)")->capture_default_str();
  app.add_option("--classes", classes_path, "class table (YAML)")->capture_default_str();
  app.add_option("--journal", journal_path,
                 "journal of every accepted input (checksummed records): replayed at start, appended while running");
  app.add_option("--out-dir", out_dir, "write TUM trajectories and the object map here: periodically, on SIGUSR1 and at exit");
  app.add_option("--write-period", write_period, "seconds between writes of the outputs (0: only on SIGUSR1 and at exit)")
      ->capture_default_str();
  app.add_flag("--background-solves", background_solves,
               "full solves on a worker thread, off the update path (experimental: at 4,000 key poses the estimate "
               "drifts; see BENCHMARKS.md)");
  app.add_option("--publish-every", publish_every, "publish map and trajectories every N updates (and on full solves)")
      ->capture_default_str();
  app.add_option("--bundle-channel", ch.bundle)->capture_default_str();
  app.add_option("--peer-bundle-channel", ch.peer_bundle)->capture_default_str();
  app.add_option("--loop-closure-channel", ch.loop_closure)->capture_default_str();
  app.add_option("--object-map-channel", ch.object_map)->capture_default_str();
  app.add_option("--trajectory-channel", ch.trajectory)->capture_default_str();
  app.add_option("--status-channel", ch.status)->capture_default_str();
  addCommonOptions(app, common);
  return runApp(app, common, argc, argv, [&]() {
    if (url.empty()) url = slide::robotBusUrl(robot);
    BackendConfig cfg = loadBackendConfig(config_path);
    cfg.background_solves = background_solves;
    const ClassTable classes = ClassTable::load(classes_path);
    lcm::LCM lcm(url);
    if (!lcm.good()) throw std::runtime_error("cannot open LCM at " + url);
    OptimizerNode node(cfg, classes, robot, ch,
                       [&](const std::string& c, const std::vector<uint8_t>& b) {
                         lcm.publish(c, b.data(), static_cast<unsigned>(b.size()));
                       },
                       publish_every);
    node.setOutputs(out_dir, write_period);
    // Asked to stop, the daemon writes its outputs at once: a full solve running inside an
    // update (the journal's replay, or without --background-solves) is aborted.
    node.optimizer().setStopFlag(&g_abort_solves);
    std::signal(SIGINT, [](int) { g_stop = 1, g_abort_solves.store(true); });
    std::signal(SIGTERM, [](int) { g_stop = 1, g_abort_solves.store(true); });
    std::signal(SIGUSR1, [](int) { g_write = 1; });
    if (!journal_path.empty()) {
      node.openJournal(journal_path);
      node.publishAll();
    }
    Receiver rx{&node};
    msg::Inbox inbox(lcm);
    for (const std::string& c : {ch.bundle, ch.peer_bundle, ch.loop_closure}) inbox.subscribeRaw(c, &Receiver::onMessage, &rx);
    node.setBusDrops([&inbox]() { return inbox.dropped(); });
    spdlog::info("robot {} optimizer on {} (in: {}, {}, {}; out: {}, {}, {})", robot, url, ch.bundle, ch.peer_bundle,
                 ch.loop_closure, ch.object_map, ch.trajectory, ch.status);
    while (!g_stop) {
      if (lcm.handleTimeout(100) < 0 && !g_stop) throw std::runtime_error("LCM receive failed on " + url);
      node.poll();
      if (g_write) {
        g_write = 0;
        node.writeOutputs();
      }
    }
    node.stop();
    const Optimizer& o = node.optimizer();
    spdlog::info("stopping: {} key poses, {} landmarks, {} peers merged, {} inputs rejected, {} undecodable, "
                 "dropped on the bus: {}", o.numKeyPoses(), o.numLandmarks(), o.numPeersMerged(), o.rejected(),
                 node.decodeErrors(), inbox.dropped() ? inbox.summary() : "none");
    return 0;
  });
}
