#include "team/sync_config.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace slide::team {

SyncConfig SyncConfig::fromConfig(const ConfigNode& n, std::optional<std::int32_t> robot) {
  SyncConfig c;
  c.robot = robot ? *robot : n.get<std::int32_t>("robot");
  c.team = n.getList<std::int32_t>("team");
  if (n.has("team_key"))
    n.fail("team_key", "a key shared by the team lets any member speak for any other; use team_key_file (per-pair "
                       "keys, slide-team-keys makes them)");
  c.team_key_file = n.get<std::string>("team_key_file", "");
  c.heartbeat_period_s = n.get<double>("heartbeat_period_s", c.heartbeat_period_s);
  c.heartbeat_idle_factor = n.get<double>("heartbeat_idle_factor", c.heartbeat_idle_factor);
  c.ack_delay_s = n.get<double>("ack_delay_s", c.ack_delay_s);
  c.resend_timeout_s = n.get<double>("resend_timeout_s", c.resend_timeout_s);
  c.relay_delay_s = n.get<double>("relay_delay_s", c.relay_delay_s);
  c.loss_grace_s = n.get<double>("loss_grace_s", c.loss_grace_s);
  c.peer_timeout_s = n.get<double>("peer_timeout_s", c.peer_timeout_s);
  c.map_period_s = n.get<double>("map_period_s", c.map_period_s);
  c.map_refresh_s = n.get<double>("map_refresh_s", c.map_refresh_s);
  c.map_delta_move_m = n.get<double>("map_delta_move_m", c.map_delta_move_m);
  c.rate_limit_bytes_per_s = n.get<double>("rate_limit_bytes_per_s", c.rate_limit_bytes_per_s);
  c.burst_bytes = n.get<double>("burst_bytes", c.burst_bytes);
  c.max_chunk_bytes = n.get<unsigned>("max_chunk_bytes", static_cast<unsigned>(c.max_chunk_bytes));
  c.bundle_hold_s = n.get<double>("bundle_hold_s", c.bundle_hold_s);
  c.max_ranges_per_origin = n.get<unsigned>("max_ranges_per_origin", static_cast<unsigned>(c.max_ranges_per_origin));
  c.max_sends_per_tick = n.get<unsigned>("max_sends_per_tick", static_cast<unsigned>(c.max_sends_per_tick));
  c.max_seq_jump = n.get<std::int32_t>("max_seq_jump", c.max_seq_jump);
  c.reassembly_bytes = n.get<unsigned>("reassembly_bytes", static_cast<unsigned>(c.reassembly_bytes));
  c.reassembly_timeout_s = n.get<double>("reassembly_timeout_s", c.reassembly_timeout_s);
  c.max_counter_ahead_s = n.get<double>("max_counter_ahead_s", c.max_counter_ahead_s);
  c.thin_observations = n.get<bool>("thin_observations", c.thin_observations);
  c.thin_travel_m = n.get<double>("thin_travel_m", c.thin_travel_m);
  c.thin_turn_deg = n.get<double>("thin_turn_deg", c.thin_turn_deg);
  c.thin_size_change_m = n.get<double>("thin_size_change_m", c.thin_size_change_m);
  c.thin_min_shares = n.get<int>("thin_min_shares", c.thin_min_shares);
  try {
    c.validate();
  } catch (const std::invalid_argument& e) {
    n.fail("", e.what());
  }
  return c;
}

void SyncConfig::validate() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0)) throw std::invalid_argument(std::string(name) + " must be positive");
  };
  positive(heartbeat_period_s, "heartbeat_period_s");
  positive(resend_timeout_s, "resend_timeout_s");
  positive(peer_timeout_s, "peer_timeout_s");
  positive(map_period_s, "map_period_s");
  positive(map_refresh_s, "map_refresh_s");
  positive(map_delta_move_m, "map_delta_move_m");
  positive(rate_limit_bytes_per_s, "rate_limit_bytes_per_s");
  positive(burst_bytes, "burst_bytes");
  positive(reassembly_timeout_s, "reassembly_timeout_s");
  if (!(max_counter_ahead_s >= 1 && max_counter_ahead_s <= 86400))
    throw std::invalid_argument("max_counter_ahead_s must be within 1..86400");
  if (!(heartbeat_idle_factor >= 1 && heartbeat_idle_factor <= 100))
    throw std::invalid_argument("heartbeat_idle_factor must be within 1..100");
  if (peer_timeout_s <= heartbeat_period_s * heartbeat_idle_factor)
    throw std::invalid_argument(
        "peer_timeout_s must exceed heartbeat_period_s * heartbeat_idle_factor (peers would drop out between heartbeats)");
  if (ack_delay_s < 0 || relay_delay_s < 0 || loss_grace_s < 0)
    throw std::invalid_argument("ack_delay_s, relay_delay_s and loss_grace_s must be >= 0");
  if (max_chunk_bytes < 64 || max_chunk_bytes > 32767)
    throw std::invalid_argument("max_chunk_bytes must be within 64..32767 (the team bus's chunk size is an int16)");
  if (!(bundle_hold_s >= 0 && bundle_hold_s <= 60)) throw std::invalid_argument("bundle_hold_s must be within 0..60");
  if (max_ranges_per_origin < 1 || max_ranges_per_origin > 4096)
    throw std::invalid_argument("max_ranges_per_origin must be within 1..4096");
  if (max_sends_per_tick < 1) throw std::invalid_argument("max_sends_per_tick must be >= 1");
  if (max_seq_jump < 1) throw std::invalid_argument("max_seq_jump must be >= 1");
  if (!(thin_travel_m >= 0) || !(thin_turn_deg >= 0) || !(thin_size_change_m >= 0) || !std::isfinite(thin_travel_m) ||
      !std::isfinite(thin_turn_deg) || !std::isfinite(thin_size_change_m))
    throw std::invalid_argument("thin_travel_m, thin_turn_deg and thin_size_change_m must be finite and >= 0");
  if (thin_min_shares < 1 || thin_min_shares > 1000) throw std::invalid_argument("thin_min_shares must be 1..1000");
  if (team.size() > 16) throw std::invalid_argument("at most 16 robots in a team (one message tag per member)");
  for (std::int32_t id : team)
    if (id < 0 || id > 32767)
      throw std::invalid_argument("team id " + std::to_string(id) + " outside 0..32767 (int16 on the team bus)");
  if (std::find(team.begin(), team.end(), robot) == team.end())
    throw std::invalid_argument("robot " + std::to_string(robot) + " is not in the team list");
}

void SyncConfig::loadKeys(std::string path) {
  if (path.empty()) path = team_key_file;
  if (path.empty()) throw std::runtime_error("no team key file (config team_key_file or --team-key-file)");
  for (auto at = path.find("{robot}"); at != std::string::npos; at = path.find("{robot}"))
    path.replace(at, 7, std::to_string(robot));
  pair_keys = loadTeamKeys(path, robot);
  for (std::int32_t id : team)
    if (id != robot && !pair_keys.count(id))
      throw std::invalid_argument("team key file " + path + ": no key for peer " + std::to_string(id) +
                                  " of the team list");
}

}  // namespace slide::team
