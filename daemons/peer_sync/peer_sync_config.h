#pragma once
// Peer sync's settings from its config (a peer-sync file, or the peer_sync section of a shared
// file) and the command line, which wins over the config.
#include <string>

#include "app/robot_bus.h"
#include "config/config.h"
#include "peer_sync_node.h"
#include "team/sync_config.h"

namespace slide {

struct PeerSyncSetup {
  team::SyncConfig sync;  // with the robot's team keys loaded
  PeerSyncChannels channels;
  std::string robot_url, team_url;
  std::string state_dir;  // created
  team::Micros tick_us = 50000, stats_us = 10000000;
  int max_deliveries = 4;  // peers' bundles published per tick
};

// Empty `team_url`, `state_dir`, `team_key_file`: the config's; without a robot bus URL on the
// command line or in the config, robot bus.robot's own bus. Throws ConfigError naming the key
// of a missing, absurd or unknown setting.
PeerSyncSetup readPeerSyncSetup(const ConfigNode& cfg, const app::RobotBusOptions& bus, const std::string& team_url,
                                const std::string& state_dir, const std::string& team_key_file);

}  // namespace slide
