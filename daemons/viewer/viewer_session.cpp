#include "viewer_session.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <filesystem>
#include <regex>
#include <stdexcept>

#include "app/robot_bus.h"
#include "objects/class_table.h"

namespace slide {

std::vector<ViewerBus> viewerBuses(const std::vector<int>& robots, const std::vector<std::string>& buses,
                                   const std::string& team_url, bool replaying) {
  if (!replaying && robots.empty() && buses.empty())
    throw std::runtime_error("nothing to show: give --robot N, --bus N=URL or --replay RUN_DIR");
  if (replaying && (!robots.empty() || !buses.empty() || !team_url.empty()))
    throw std::runtime_error("--replay plays logs; it does not mix with --robot, --bus or --team-url");
  std::vector<ViewerBus> out;
  for (int r : robots) out.push_back({false, r, app::robotBusUrl(r)});
  static const std::regex re(R"((\d{1,9})=(.+))");
  for (const std::string& b : buses) {
    std::smatch m;
    if (!std::regex_match(b, m, re)) throw std::runtime_error("--bus '" + b + "': expected N=URL (robot N's bus)");
    out.push_back({false, std::stoi(m[1]), m[2]});
  }
  if (!team_url.empty()) out.push_back({true, -1, team_url});
  return out;
}

nlohmann::json viewerLegend(const ClassTable& table) {
  nlohmann::json classes = nlohmann::json::object();
  for (int id : table.ids()) {
    const ClassInfo& c = table.at(id);
    classes[std::to_string(id)] = {{"name", c.name}, {"shape", shapeName(c.shape)},
                                   {"color", {c.color[0], c.color[1], c.color[2]}}};
  }
  return classes;
}

ViewerSession::ViewerSession(nlohmann::json classes, const ViewerNodeParams& params)
    : classes_(std::move(classes)), node_(scene_, params) {}

void ViewerSession::startReplay(const std::vector<std::string>& replay, bool follow, double wall) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<LogSource> sources;
  for (const std::string& r : replay) {
    if (follow && std::filesystem::is_directory(r)) {
      follow_dirs_.push_back(r);
      try {
        for (const LogSource& s : logSourcesOf(r)) sources.push_back(s);
      } catch (const std::runtime_error& e) {
        spdlog::info("{}; waiting for its logs", e.what());
      }
      continue;
    }
    for (const LogSource& s : logSourcesOf(r)) sources.push_back(s);
  }
  follow_ = follow;
  player_ = std::make_unique<LogPlayer>(sources, node_, scene_, follow, wall);
  spdlog::info("replaying {} logs ({} events the viewer draws){}", sources.size(), player_->events(),
               follow ? ", following them as they grow" : "");
}

bool ViewerSession::onBus(bool team, int robot, const std::string& channel, const void* data, std::size_t size,
                          double wall) {
  std::lock_guard<std::mutex> lock(mutex_);
  return team ? node_.onTeamBus(robot, channel, data, size, wall) : node_.onRobotBus(robot, channel, data, size, wall);
}

std::string ViewerSession::dropSummary() {
  std::lock_guard<std::mutex> lock(mutex_);
  return node_.dropSummary();
}

std::string ViewerSession::update(ClientCursor& c, double now, double wall) {
  std::lock_guard<std::mutex> lock(mutex_);
  const bool changed = c.epoch != scene_.epoch() || c.version != scene_.version();
  if (!changed && now - c.last_status_s < 1.0) return "";
  nlohmann::json out = scene_.delta(c.epoch, c.version);
  if (out["reset"].get<bool>()) out["classes"] = classes_;
  nlohmann::json status = {{"mode", player_ ? (follow_ ? "follow" : "replay") : "live"},
                           {"received", node_.received()},
                           {"dropped", node_.dropped()},
                           {"dropped_objects", node_.droppedObjects()}};
  if (player_) status["replay"] = player_->clock().status(wall);
  out["status"] = std::move(status);
  c.last_status_s = now;
  c.epoch = scene_.epoch();
  c.version = scene_.version();
  return out.dump();
}

bool ViewerSession::control(const std::string& text, double wall) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object() || !j.contains("cmd") || !j["cmd"].is_string()) return false;
  const std::string cmd = j["cmd"];
  const double value = j.contains("value") && j["value"].is_number() ? j["value"].get<double>() : NAN;
  std::lock_guard<std::mutex> lock(mutex_);
  if (!player_) return false;
  viewer::ReplayClock& clock = player_->clock();
  if (cmd == "pause") clock.pause(wall);
  else if (cmd == "play") clock.play(wall);
  else if (cmd == "live") clock.goLive();
  else if (cmd == "speed" && std::isfinite(value)) clock.setSpeed(value, wall);
  else if (cmd == "seek" && std::isfinite(value)) clock.seek(value, wall);
  else return false;
  return true;
}

std::string ViewerSession::stats(const WebServerStats& s) {
  std::lock_guard<std::mutex> lock(mutex_);
  const nlohmann::json j = {{"bytes_sent", s.bytes_sent},         {"messages_sent", s.messages_sent},
                            {"clients", s.clients_now},           {"clients_total", s.clients_total},
                            {"clients_refused", s.clients_refused}, {"controls", s.controls},
                            {"controls_refused", s.controls_refused}, {"received", node_.received()},
                            {"dropped", node_.dropped()},         {"drops", node_.dropSummary()},
                            {"scene_version", scene_.version()}};
  return j.dump();
}

void ViewerSession::step(double now, double wall) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!player_) {
    scene_.tick(wall);
    return;
  }
  if (follow_ && now - last_read_ >= 0.5) {
    for (const std::string& d : follow_dirs_) {
      try {
        player_->addSources(logSourcesOf(d));
      } catch (const std::runtime_error&) {  // no logs there yet
      }
    }
    player_->readMore(wall);
    last_read_ = now;
  }
  player_->advance(wall);
}

std::string ViewerSession::summary() {
  std::lock_guard<std::mutex> lock(mutex_);
  return std::to_string(node_.received()) + " messages drawn, " + std::to_string(node_.dropped()) + " dropped" +
         (node_.dropped() ? ": " + node_.dropSummary() : "");
}

void ViewerSession::logTraffic(const WebServer& server, double now) {
  if (last_report_ < 0) last_report_ = now;
  if (now - last_report_ < 10.0) return;
  const WebServerStats s = server.stats();
  spdlog::info("{} browsers, {:.1f} KB/s to them; {}", s.clients_now,
               static_cast<double>(s.bytes_sent - last_bytes_) / 1024.0 / (now - last_report_), summary());
  last_bytes_ = s.bytes_sent;
  last_report_ = now;
}

}  // namespace slide
