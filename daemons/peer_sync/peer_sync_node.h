#pragma once
// The peer-sync daemon's logic without the LCM loop: moves messages between the two buses and
// the peer-sync engine (team::PeerSyncNode). Own bundles and maps come in from the robot bus,
// team frames from the team bus, as raw bytes (a team frame's payload is decoded only after its
// MAC passed); each step sends the engine's heartbeats, acks and chunks on the team bus and
// delivers peers' bundles (paced) and maps on the robot bus, through injected publishers.
// Malformed input is dropped and counted, never fatal.
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "app/channels.h"
#include "config/config.h"
#include "msg/publisher.h"
#include "team/peer_sync.h"

namespace slide {

struct PeerSyncChannels {
  std::string own_bundle = app::channels::kKeyPoseBundle;  // robot bus, in
  std::string own_map = app::channels::kOwnMap;         // robot bus, in
  std::string peer_bundle = app::channels::kPeerBundle;    // robot bus, out
  std::string peer_map = app::channels::kPeerMap;          // robot bus, out
  std::string status = app::channels::kPeerSyncStatus;     // robot bus, out
  team::TeamChannels team;                            // team bus
};

// The config's `channels:` section.
PeerSyncChannels readPeerSyncChannels(const ConfigNode& cfg);

// A team frame holds at most 32767 payload bytes (sync_chunk_t) or 32767 origins of a few
// ranges each (heartbeat, ack); anything longer is not a frame of ours.
constexpr std::size_t kMaxTeamFrameBytes = 1u << 20;

class PeerSyncDaemon {
 public:
  // The bus layer's side of the counts: `undecodable(channel, why)` counts an own input that
  // does not decode; `summaries()` gives the bus layer's drop lines for the stats log.
  struct BusDrops {
    std::function<void(const std::string& channel, const std::string& why)> undecodable;
    std::function<std::vector<std::string>()> summaries;
  };

  PeerSyncDaemon(team::PeerSyncNode& node, PeerSyncChannels channels, int max_deliveries, msg::Publisher robot_bus,
                 msg::Publisher team_bus, BusDrops bus_drops);

  // Logs what the engine found in its journal and counters at start (`state_dir` names them).
  void logStart(const std::string& state_dir) const;

  // Robot bus, in (`now`: the engine's clock, µs).
  void onOwnBundle(const std::string& channel, const void* data, std::size_t size, team::Micros now);
  void onOwnMap(const std::string& channel, const void* data, std::size_t size, team::Micros now);
  // Team bus, in: a heartbeat, chunk or ack by its channel.
  void onTeam(const std::string& channel, const void* data, std::size_t size, team::Micros now);

  // Sends what the engine has to send and delivers peers' bundles and maps.
  void step(team::Micros now);
  // Logs holdings, traffic and drops and publishes them on the status channel.
  void logStats(team::Micros now);

 private:
  template <typename L>
  void onTeamMessage(const std::string& channel, const void* data, std::size_t size, team::Micros now);
  void undecodable(const std::string& channel, const std::string& why);
  void alarmOnWriteFailures();

  team::PeerSyncNode& node_;
  PeerSyncChannels channels_;
  int max_deliveries_;
  msg::Publisher robot_bus_, team_bus_;
  BusDrops bus_drops_;
  std::uint64_t alarmed_failures_ = 0;
  std::chrono::steady_clock::time_point last_alarm_{};
};

}  // namespace slide
