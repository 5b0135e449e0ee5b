// slide-viewer: one web page (HTTP + WebSocket, 127.0.0.1 by default) that draws, live, what
// robots' buses say (object maps, trajectories, key poses, instances, loop closures, status)
// and what the team bus carries; or replays a recorded run into the same page. Only listens.
#include <spdlog/spdlog.h>

#include <lcm/lcm-cpp.hpp>

#include "app/app.h"
#include "app/clock.h"
#include "app/stop_signal.h"
#include "msg/bus_wait.h"
#include "msg/inbox.h"
#include "objects/class_table.h"
#include "viewer_session.h"

using namespace slide;

int main(int argc, char** argv) {
  CLI::App app{"Live map viewer: serves one web page that draws robots' object maps, trajectories, key poses,\n"
               "instances, loop closures, team links and status from their buses (or a recorded run) in 3-D.",
               "slide-viewer"};
  app::CommonOptions common;
  std::vector<int> robots;
  std::vector<std::string> buses, replay;
  std::string team_url;
  bool follow = false;
  WebServerOptions web;
  web.web_root = std::string(SLIDE_SOURCE_DIR) + "/daemons/viewer/web";
  ViewerNodeParams params;
  std::string classes_path = std::string(SLIDE_SOURCE_DIR) + "/config/classes.yaml";
  app.add_option("--classes", classes_path, "Class table (names and colours of the legend)")->capture_default_str();
  app.add_option("--robot", robots, "Listen to robot N's bus at its default URL (repeat for several robots)");
  app.add_option("--bus", buses, "Listen to robot N's bus at URL: N=URL (repeatable)");
  app.add_option("--team-url", team_url, "Also listen to the team bus at this URL (links and traffic)");
  app.add_option("--replay", replay,
                 "Replay instead of listening: a run folder (its logs/robot<N>.lcmlog, logs/team<N>.lcmlog), a log "
                 "named robot<N>/team<N>*.lcmlog, or N=LOG / team:N=LOG (repeatable)");
  app.add_flag("--follow", follow, "With --replay: keep reading the logs as they grow and stay at their end (live)");
  addWebServerOptions(app, web);
  app.add_option("--max-instance-points", params.max_instance_points, "Points of a scan's instances sent (thinned)")
      ->capture_default_str();
  app::addCommonOptions(app, common);
  return app::runApp(app, common, argc, argv, [&]() {
    checkWebRoot(web.web_root);
    const std::vector<ViewerBus> bus_list = viewerBuses(robots, buses, team_url, !replay.empty());
    ViewerSession session(viewerLegend(ClassTable::load(classes_path)), params);
    if (!replay.empty()) session.startReplay(replay, follow, app::wallSeconds());
    std::vector<std::unique_ptr<lcm::LCM>> lcms;
    std::vector<lcm::LCM*> fds;
    std::vector<std::unique_ptr<msg::Inbox>> inboxes;
    const ViewerChannels ch;
    for (const ViewerBus& b : bus_list) {
      lcms.push_back(std::make_unique<lcm::LCM>(b.url));
      if (!lcms.back()->good()) throw std::runtime_error("cannot open LCM at '" + b.url + "'");
      fds.push_back(lcms.back().get());
      msg::Inbox& inbox = *inboxes.emplace_back(std::make_unique<msg::Inbox>(*lcms.back()));
      for (const std::string& c : b.team ? ch.teamBus() : ch.robotBus())
        inbox.subscribeBytes(c, [&session, &inbox, b](const std::string& channel, const void* data, std::size_t size) {
          if (!session.onBus(b.team, b.robot, channel, data, size, app::wallSeconds()))
            inbox.countUndecodable(channel, session.dropSummary());
        });
      // Only the newest scan's instances are drawn: a viewer that falls behind skips old ones.
      if (!b.team) inbox.setQueueCapacity(ch.instances, 10);
      spdlog::info("listening to {} on {}", b.team ? "the team bus" : "robot " + std::to_string(b.robot) + "'s bus", b.url);
    }
    WebServer server(
        web, [&](ClientCursor& c) { return session.update(c, app::steadySeconds(), app::wallSeconds()); },
        [&](const std::string& text) { return session.control(text, app::wallSeconds()); },
        [&](const WebServerStats& s) { return session.stats(s); });
    app::installStopHandlers();
    spdlog::info("viewer at {} (over SSH: ssh -L {}:127.0.0.1:{} <robot>, then open http://127.0.0.1:{}/)", server.url(),
                 web.port, web.port, web.port);
    while (!app::stopRequested()) {
      session.step(app::steadySeconds(), app::wallSeconds());
      msg::handleAny(fds, 50000);
      session.logTraffic(server, app::steadySeconds());
    }
    spdlog::info("stopping; {} bytes sent to browsers; {}", server.stats().bytes_sent, session.summary());
    return 0;
  });
}
