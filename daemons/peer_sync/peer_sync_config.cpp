#include "peer_sync_config.h"

#include <filesystem>

#include "app/app.h"

namespace slide {

PeerSyncSetup readPeerSyncSetup(const ConfigNode& cfg, const app::RobotBusOptions& bus, const std::string& team_url,
                                const std::string& state_dir, const std::string& team_key_file) {
  PeerSyncSetup s;
  s.sync = team::SyncConfig::fromConfig(cfg, bus.robot);
  s.sync.loadKeys(team_key_file);
  s.channels = readPeerSyncChannels(cfg);
  s.robot_url = bus.url.empty() ? bus.resolve(cfg.get<std::string>("robot_url", "")) : bus.url;
  s.team_url = team_url.empty() ? cfg.get<std::string>("team_url") : team_url;
  s.state_dir = state_dir;
  if (s.state_dir.empty()) {
    std::string base = cfg.get<std::string>("state_dir", "");
    if (base.empty()) base = app::persistentStateDir() + "/peer-sync";
    s.state_dir = base + "/robot" + std::to_string(bus.robot);
  }
  const double tick_s = cfg.get<double>("tick_period_s", 0.05);
  const double stats_s = cfg.get<double>("stats_period_s", 10.0);
  s.max_deliveries = cfg.get<int>("max_deliveries_per_tick", s.max_deliveries);
  if (s.max_deliveries < 1) cfg.fail("max_deliveries_per_tick", "must be at least 1");
  if (!(tick_s > 0) || !(stats_s > 0)) cfg.fail("tick_period_s", "tick_period_s and stats_period_s must be positive");
  s.tick_us = static_cast<team::Micros>(tick_s * 1e6);
  s.stats_us = static_cast<team::Micros>(stats_s * 1e6);
  cfg.known({"robot", "robot_url", "team_url", "state_dir"});  // read above unless the command line set them
  cfg.rejectUnknownKeys();  // this file, or its peer_sync section of a shared file
  std::filesystem::create_directories(s.state_dir);
  return s;
}

}  // namespace slide
