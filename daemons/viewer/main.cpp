// slide-viewer: one web page (HTTP + WebSocket, 127.0.0.1 by default) that draws, live, what
// robots' buses say (object maps, trajectories, key poses, instances, loop closures, status)
// and what the team bus carries; or replays a recorded run into the same page. Only listens.
#include <lcm/lcm-cpp.hpp>
#include <poll.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <map>
#include <regex>

#include "app/app.h"
#include "app/clock.h"
#include "app/robot_bus.h"
#include "app/stop_signal.h"
#include "objects/class_table.h"
#include "msg/inbox.h"
#include "viewer_session.h"

using namespace slide;

namespace {
struct Bus {
  bool team = false;
  int robot = -1;  // robot bus: whose; team bus: -1 (heard by this host)
  std::string url;
  std::unique_ptr<lcm::LCM> lcm;
  std::unique_ptr<msg::Inbox> inbox;
};

// "N=URL" -> (N, URL); throws naming the option.
std::pair<int, std::string> robotUrl(const std::string& s) {
  static const std::regex re(R"((\d+)=(.+))");
  std::smatch m;
  if (!std::regex_match(s, m, re)) throw std::runtime_error("--bus '" + s + "': expected N=URL (robot N's bus)");
  return {std::stoi(m[1]), m[2]};
}

double wallSeconds() { return static_cast<double>(wallMicros()) * 1e-6; }

// Opens bus `b` and feeds the channels the viewer draws into `session`.
void subscribe(Bus& b, ViewerSession& session) {
  b.lcm = std::make_unique<lcm::LCM>(b.url);
  if (!b.lcm->good()) throw std::runtime_error("cannot open LCM at '" + b.url + "'");
  b.inbox = std::make_unique<msg::Inbox>(*b.lcm);
  const ViewerChannels ch;
  const std::vector<std::string> channels =
      b.team ? std::vector<std::string>{ch.team_heartbeat, ch.team_chunk, ch.team_ack}
             : std::vector<std::string>{ch.object_map,   ch.trajectory,       ch.keypose_bundle, ch.instances,
                                        ch.loop_closure, ch.optimizer_status, ch.sensor_status};
  for (const std::string& c : channels)
    b.inbox->subscribeBytes(c, [&session, bp = &b](const std::string& channel, const void* data, std::size_t size) {
      if (!session.onBus(bp->team, bp->robot, channel, data, size, wallSeconds()))
        bp->inbox->countUndecodable(channel, session.dropSummary());
    });
  // Only the newest scan's instances are drawn: a viewer that falls behind skips old ones.
  if (!b.team) b.inbox->setQueueCapacity(ch.instances, 10);
  spdlog::info("listening to {} on {}", b.team ? "the team bus" : "robot " + std::to_string(b.robot) + "'s bus", b.url);
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Live map viewer: serves one web page that draws robots' object maps, trajectories, key poses,\n"
               "instances, loop closures, team links and status from their buses (or a recorded run) in 3-D.",
               "slide-viewer"};
  CommonOptions common;
  addCommonOptions(app, common);
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
  app.add_option("--bind", web.bind, "Address to serve on (127.0.0.1: this host only; tunnel with ssh -L)")
      ->capture_default_str();
  app.add_option("--port", web.port, "HTTP port")->capture_default_str()->check(CLI::Range(1, 65535));
  app.add_option("--web-root", web.web_root, "Folder with the page (index.html, viewer.js, node_modules/three)")
      ->capture_default_str();
  app.add_option("--max-clients", web.max_clients, "Browsers at once")->capture_default_str()->check(CLI::Range(1, 256));
  app.add_option("--request-timeout-ms", web.request_timeout_ms,
                 "A request not complete, or a browser not reading, for this long is dropped")
      ->capture_default_str()
      ->check(CLI::Range(100, 600000));
  app.add_option("--period", web.period_s, "Seconds between updates to a browser")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 10.0));
  app.add_option("--max-instance-points", params.max_instance_points, "Points of a scan's instances sent (thinned)")
      ->capture_default_str();
  return runApp(app, common, argc, argv, [&]() {
    const std::string three = web.web_root + "/node_modules/three/build/three.module.min.js";
    if (!std::filesystem::exists(web.web_root + "/index.html"))
      throw std::runtime_error("--web-root " + web.web_root + ": no index.html");
    if (!std::filesystem::exists(three))
      throw std::runtime_error(three + " missing: run ./slide setup (npm ci in " + web.web_root + ")");
    if (replay.empty() && robots.empty() && buses.empty())
      throw std::runtime_error("nothing to show: give --robot N, --bus N=URL or --replay RUN_DIR");
    if (!replay.empty() && (!robots.empty() || !buses.empty() || !team_url.empty()))
      throw std::runtime_error("--replay plays logs; it does not mix with --robot, --bus or --team-url");

    nlohmann::json classes = nlohmann::json::object();
    const ClassTable table = ClassTable::load(classes_path);
    for (int id : table.ids()) {
      const ClassInfo& c = table.at(id);
      classes[std::to_string(id)] = {{"name", c.name}, {"shape", shapeName(c.shape)},
                                     {"color", {c.color[0], c.color[1], c.color[2]}}};
    }

    ViewerSession session(std::move(classes), params);
    std::vector<Bus> bus_list;
    if (!replay.empty()) {
      session.startReplay(replay, follow, wallSeconds());
    } else {
      for (int r : robots) bus_list.push_back({false, r, robotBusUrl(r), nullptr, nullptr});
      for (const std::string& b : buses) {
        auto [r, url] = robotUrl(b);
        bus_list.push_back({false, r, url, nullptr, nullptr});
      }
      if (!team_url.empty()) bus_list.push_back({true, -1, team_url, nullptr, nullptr});
      for (Bus& b : bus_list) subscribe(b, session);
    }
    std::unique_ptr<WebServer> server;
    server = std::make_unique<WebServer>(
        web, [&](ClientCursor& c) { return session.update(c, steadySeconds(), wallSeconds()); },
        [&](const std::string& text) { return session.control(text, wallSeconds()); },
        [&]() { return session.stats(server->stats()); });
    installStopHandlers();
    spdlog::info("viewer at {} (over SSH: ssh -L {}:127.0.0.1:{} <robot>, then open http://127.0.0.1:{}/)", server->url(),
                 web.port, web.port, web.port);

    double last_report = steadySeconds();
    std::uint64_t last_bytes = 0;
    std::vector<pollfd> fds;
    for (Bus& b : bus_list) fds.push_back({b.lcm->getFileno(), POLLIN, 0});
    while (!stopRequested()) {
      session.step(steadySeconds(), wallSeconds());
      for (pollfd& p : fds) p.revents = 0;
      if (poll(fds.data(), fds.size(), 50) < 0 && !stopRequested()) throw std::runtime_error("poll on the buses failed");
      for (std::size_t i = 0; i < fds.size(); ++i)
        if (fds[i].revents & POLLIN) bus_list[i].lcm->handle();
      const double now = steadySeconds();
      if (now - last_report >= 10.0) {
        const WebServerStats st = server->stats();
        spdlog::info("{} browsers, {:.1f} KB/s to them; {}", st.clients_now,
                     static_cast<double>(st.bytes_sent - last_bytes) / 1024.0 / (now - last_report), session.summary());
        last_bytes = st.bytes_sent;
        last_report = now;
      }
    }
    spdlog::info("stopping; {} bytes sent to browsers; {}", server->stats().bytes_sent, session.summary());
    server.reset();
    return 0;
  });
}
