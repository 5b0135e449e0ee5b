#pragma once
// The viewer's shared state behind its web server: the scene, the node that fills it from bus
// messages, and (replaying) the log player. The server's threads ask for each browser's next
// update, replay controls and /stats; the daemon's loop feeds bus messages and steps the replay.
// One mutex guards it all.
#include <cstdint>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "log_player.h"
#include "viewer/scene.h"
#include "viewer_node.h"
#include "web_server.h"

namespace slide {

class ClassTable;

// One bus the viewer listens to: robot `robot`'s bus, or the team bus (robot -1: as this host
// hears it).
struct ViewerBus {
  bool team = false;
  int robot = -1;
  std::string url;
};

// The buses of --robot N (at robotBusUrl(N)), --bus N=URL and --team-url, in that order; none
// when replaying. Throws naming the option for a --bus that is not N=URL, when there is nothing
// to show, or when `replaying` is mixed with buses.
std::vector<ViewerBus> viewerBuses(const std::vector<int>& robots, const std::vector<std::string>& buses,
                                   const std::string& team_url, bool replaying);

// The page's legend: class id -> name, shape and colour, for every class of `table`.
nlohmann::json viewerLegend(const ClassTable& table);

class ViewerSession {
 public:
  // `classes`: the legend (viewerLegend), sent with every full copy.
  ViewerSession(nlohmann::json classes, const ViewerNodeParams& params);

  // Replays the logs named by `replay` (run folders, logs; log_player.h). With `follow`, keeps
  // reading them as they grow, and takes up logs that appear later in the run folders.
  void startReplay(const std::vector<std::string>& replay, bool follow, double wall);
  bool replaying() const { return player_ != nullptr; }

  // One bus message (robot bus of `robot`, or the team bus heard by `robot`, -1: this host);
  // false when dropped (its reason in dropSummary()).
  bool onBus(bool team, int robot, const std::string& channel, const void* data, std::size_t size, double wall);
  std::string dropSummary();

  // The next update for a browser at cursor `c` (empty: nothing new), as JSON text.
  std::string update(ClientCursor& c, double now, double wall);
  // A browser's replay control ({"cmd": pause|play|live|speed|seek, "value": x}); false when refused.
  bool control(const std::string& text, double wall);
  // /stats: the server's figures with the node's.
  std::string stats(const WebServerStats& s);
  // Between messages: the replay advances (and, following, reads what the logs gained every
  // 0.5 s); live, the scene ages its team links.
  void step(double now, double wall);
  // "N messages drawn, M dropped: ..." for the periodic log line.
  std::string summary();
  // Every 10 s (steady `now`): logs the browsers of `server`, the rate sent to them and summary().
  void logTraffic(const WebServer& server, double now);

 private:
  std::mutex mutex_;
  nlohmann::json classes_;
  viewer::Scene scene_;
  ViewerNode node_;
  std::unique_ptr<LogPlayer> player_;
  bool follow_ = false;
  std::vector<std::string> follow_dirs_;  // run folders whose logs may appear later
  double last_read_ = 0;
  double last_report_ = -1;  // steady s; < 0: not yet
  std::uint64_t last_bytes_ = 0;
};

}  // namespace slide
