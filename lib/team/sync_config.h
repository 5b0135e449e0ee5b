#pragma once
// Parameters of the peer-sync protocol (times in seconds, sizes in bytes).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "config/config.h"
#include "team/observation_thinning.h"
#include "team/team_keys.h"

namespace slide::team {

struct SyncConfig {
  std::int32_t robot = 0;
  std::vector<std::int32_t> team;  // every robot id allowed on the team bus (robot included)
  // The keys this robot shares with each other member (team_keys.h), read from team_key_file.
  PairKeys pair_keys;
  std::string team_key_file;       // "{robot}" in it stands for the robot id

  double heartbeat_period_s = 8.0;
  double heartbeat_idle_factor = 3.0;  // without news the period doubles up to this many times it
  double ack_delay_s = 24.0;         // acknowledgements are coalesced this long (a heartbeat acks all)
  double resend_timeout_s = 4.0;     // unacknowledged data is sent again after this at the earliest,
  double loss_grace_s = 0.5;         // once a heartbeat sent this long after it still lacks it
  double relay_delay_s = 10.0;       // a third robot's bundle is relayed once a peer lacked it this long
  double peer_timeout_s = 40.0;      // a peer is in reach while heard within this
  double map_period_s = 90.0;        // own map sent at most this often when it changed
  double map_refresh_s = 120.0;      // and again this often while a peer in reach lacks it
  double map_delta_move_m = 0.1;     // map changes: an object moved or resized by more is sent again
  double rate_limit_bytes_per_s = 20000;
  double burst_bytes = 8000;
  std::size_t max_chunk_bytes = 1024;       // payload bytes per chunk
  double bundle_hold_s = 20.0;               // own new bundles wait this long to share a chunk
  std::size_t max_ranges_per_origin = 64;   // in heartbeats and acks
  std::size_t max_sends_per_tick = 64;      // bundles considered per peer and tick
  std::int32_t max_seq_jump = 100000;       // a received seq further ahead of all held is refused
  std::size_t reassembly_bytes = 4 << 20;   // space for partly received payloads
  double reassembly_timeout_s = 30.0;
  // A sender's message counter (µs of its clock, counters.h) may lead this robot's clock by this
  // much; beyond it the message is dropped as future_counter. Team clocks must agree this well.
  double max_counter_ahead_s = 300.0;
  // Own observations shared on the team bus (observation_thinning.h): a track's first
  // thin_min_shares observations, then again only after this much travel or turn, or a class,
  // shape or size change.
  bool thin_observations = true;
  double thin_travel_m = 10.0;
  double thin_turn_deg = 45.0;
  double thin_size_change_m = 1.0;
  int thin_min_shares = 3;

  ThinningPolicy thinning() const {
    return {thin_observations, thin_travel_m, thin_turn_deg, thin_size_change_m, thin_min_shares};
  }

  // Throws ConfigError naming the file and key on a missing or invalid value. `robot`, when
  // given (the daemon's --robot), replaces the file's optional `robot` key. Keys are not read
  // here: see loadKeys().
  static SyncConfig fromConfig(const ConfigNode& node, std::optional<std::int32_t> robot = std::nullopt);
  // Throws std::invalid_argument explaining the first inconsistent value.
  void validate() const;
  // Reads pair_keys from `path` (team_key_file when empty, "{robot}" replaced by the robot id);
  // throws std::runtime_error naming the file, std::invalid_argument for a missing pair key.
  void loadKeys(std::string path = {});
};

}  // namespace slide::team
