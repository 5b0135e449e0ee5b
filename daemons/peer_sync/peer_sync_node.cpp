#include "peer_sync_node.h"

#include <spdlog/spdlog.h>

#include "app/clock.h"
#include "msg/convert.h"
#include "slide/peer_sync_status_t.hpp"
#include "team_msg.h"

namespace slide {

using team::Drop;

PeerSyncChannels readPeerSyncChannels(const ConfigNode& cfg) {
  PeerSyncChannels ch;
  if (!cfg.has("channels")) return ch;
  const ConfigNode c = cfg.child("channels");
  ch.own_bundle = c.get<std::string>("own_bundle", ch.own_bundle);
  ch.own_map = c.get<std::string>("own_map", ch.own_map);
  ch.peer_bundle = c.get<std::string>("peer_bundle", ch.peer_bundle);
  ch.peer_map = c.get<std::string>("peer_map", ch.peer_map);
  ch.status = c.get<std::string>("status", ch.status);
  ch.team.heartbeat = c.get<std::string>("heartbeat", ch.team.heartbeat);
  ch.team.chunk = c.get<std::string>("chunk", ch.team.chunk);
  ch.team.ack = c.get<std::string>("ack", ch.team.ack);
  return ch;
}

PeerSyncDaemon::PeerSyncDaemon(team::PeerSyncNode& node, PeerSyncChannels channels, int max_deliveries,
                               msg::Publisher robot_bus, msg::Publisher team_bus, BusDrops bus_drops)
    : node_(node),
      channels_(std::move(channels)),
      max_deliveries_(max_deliveries),
      robot_bus_(std::move(robot_bus)),
      team_bus_(std::move(team_bus)),
      bus_drops_(std::move(bus_drops)) {}

void PeerSyncDaemon::logStart(const std::string& state_dir) const {
  const int robot = node_.config().robot;
  for (const auto& w : node_.counters().warnings()) spdlog::warn("robot {}: {}", robot, w);
  const auto& rec = node_.db().recovery();
  if (rec.skipped)
    spdlog::warn("robot {}: journal {}: skipped {} records it cannot use (first: {})", robot, state_dir, rec.skipped,
                 rec.first_skipped);
  spdlog::info("robot {}: journal {} holds {} bundles ({} records){}", robot, state_dir, node_.db().size(), rec.records,
               rec.dropped_bytes ? fmt::format(", cut a damaged tail of {} bytes ({})", rec.dropped_bytes,
                                               rec.not_saved.empty() ? "saved to " + rec.damaged_copy : rec.not_saved)
                                 : std::string());
}

void PeerSyncDaemon::onOwnBundle(const std::string& channel, const void* data, std::size_t size, team::Micros now) {
  std::string why = "undecodable keypose_bundle_t";
  auto m = team::decodeLcm<keypose_bundle_t>(data, size);
  std::optional<KeyPoseBundle> b = m ? team::acceptBundle(*m, &why) : std::nullopt;
  if (!b) return undecodable(channel, why);
  const std::uint64_t lost = node_.dropped(Drop::Lost);
  if (auto drop = node_.addOwnBundle(std::move(*b), now))
    spdlog::warn("{}: dropped own bundle {}/{}: {}", channel, m->header.robot, m->header.seq, team::dropName(*drop));
  else if (node_.dropped(Drop::Lost) > lost)
    spdlog::warn("{}: own bundles {}..{} never arrived: peers learn the gap with bundle {}", channel,
                 m->header.seq - static_cast<std::int64_t>(node_.dropped(Drop::Lost) - lost), m->header.seq - 1,
                 m->header.seq);
}

void PeerSyncDaemon::onOwnMap(const std::string& channel, const void* data, std::size_t size, team::Micros now) {
  std::string why = "undecodable object_map_t";
  auto m = team::decodeLcm<object_map_t>(data, size);
  std::optional<team::SharedMap> map = m ? team::fromLcm(*m, &why) : std::nullopt;
  if (!map) return undecodable(channel, why);
  node_.setOwnMap(std::move(*map), now);
}

void PeerSyncDaemon::onTeam(const std::string& channel, const void* data, std::size_t size, team::Micros now) {
  if (channel == channels_.team.heartbeat) onTeamMessage<sync_heartbeat_t>(channel, data, size, now);
  else if (channel == channels_.team.chunk) onTeamMessage<sync_chunk_t>(channel, data, size, now);
  else if (channel == channels_.team.ack) onTeamMessage<sync_ack_t>(channel, data, size, now);
}

void PeerSyncDaemon::undecodable(const std::string& channel, const std::string& why) {
  if (bus_drops_.undecodable) bus_drops_.undecodable(channel, why);
}

template <typename L>
void PeerSyncDaemon::onTeamMessage(const std::string& channel, const void* data, std::size_t size, team::Micros now) {
  std::string why = "undecodable message";
  auto m = team::decodeLcm<L>(data, size);
  auto msg = m ? team::fromLcm(*m, &why) : std::nullopt;
  if (!msg) {
    node_.countMalformed();
    return spdlog::debug("{}: dropped malformed message: {}", channel, why);
  }
  node_.receive(*msg, now);
}

void PeerSyncDaemon::step(team::Micros now) {
  const team::TickOutput out = node_.tick(now);
  auto send = [this](const std::string& channel, const auto& m) {
    if (!team_bus_(channel, msg::encodeLcm(team::toLcm(m)))) spdlog::warn("{}: publish failed", channel);
  };
  for (const auto& h : out.heartbeats) send(channels_.team.heartbeat, h);
  for (const auto& a : out.acks) send(channels_.team.ack, a);
  for (const auto& c : out.chunks) send(channels_.team.chunk, c);
  // Paced: a burst (after a link comes back) must not overrun the subscribers' UDP buffers.
  for (int k = 0; k < max_deliveries_; ++k) {
    auto b = node_.nextDelivery();
    if (!b) break;
    if (!robot_bus_(channels_.peer_bundle, msg::encodeLcm(msg::toLcm(*b)))) {  // not recorded: tried again next step
      spdlog::warn("{}: publish of bundle {}/{} failed", channels_.peer_bundle, b->robot, b->seq);
      break;
    }
    node_.confirmDelivered(b->robot, b->seq);
    spdlog::debug("delivered bundle {}/{}", b->robot, b->seq);
  }
  for (const auto& map : node_.takeMaps()) {
    robot_bus_(channels_.peer_map, msg::encodeLcm(team::toLcm(map)));
    spdlog::info("map of robot {} ({} objects) delivered", map.robot, map.objects.size());
  }
  alarmOnWriteFailures();
}

// A full disk is an alarm, not a crash: an error at the first failed write and every 10 s
// while more fail; the count goes out in every status.
void PeerSyncDaemon::alarmOnWriteFailures() {
  const std::uint64_t n = node_.stateWriteFailures();
  if (n == alarmed_failures_) return;
  const auto t = std::chrono::steady_clock::now();
  if (alarmed_failures_ != 0 && t - last_alarm_ < std::chrono::seconds(10)) return;
  const std::string& journal = node_.db().lastJournalError();
  const std::string& counters = node_.counters().lastWriteError();
  spdlog::error("STATE WRITE FAILED: {} writes of the journal or counters.txt failed so far (last: {}{}{}); bundles "
                "not journalled are not taken, peers send them again",
                n, journal, !journal.empty() && !counters.empty() ? "; " : "", counters);
  alarmed_failures_ = n;
  last_alarm_ = t;
}

void PeerSyncDaemon::logStats(team::Micros now) {
  std::string drops;
  for (int d = 0; d < static_cast<int>(Drop::kCount); ++d)
    if (node_.drops()[d]) drops += fmt::format(" {}={}", team::dropName(static_cast<Drop>(d)), node_.drops()[d]);
  spdlog::info("held {} bundles, sent {:.0f} B, received {:.0f} B; drops:{}", node_.db().size(),
               node_.traffic().totalSent(), node_.traffic().totalReceived(), drops.empty() ? " none" : drops);
  if (bus_drops_.summaries)
    for (const std::string& line : bus_drops_.summaries()) spdlog::info("dropped before decoding: {}", line);
  for (const auto& line : node_.trafficSummary(now)) spdlog::info("{}", line);
  // The same counts for whoever watches the robot bus.
  peer_sync_status_t st;
  st.utime = app::wallMicros();
  st.robot = node_.config().robot;
  st.held_bundles = static_cast<int32_t>(node_.db().size());
  st.bytes_sent = node_.traffic().totalSent();
  st.bytes_received = node_.traffic().totalReceived();
  for (int d = 0; d < static_cast<int>(Drop::kCount); ++d) {
    st.drop_reasons.push_back(team::dropName(static_cast<Drop>(d)));
    st.drop_counts.push_back(static_cast<int64_t>(node_.drops()[d]));
  }
  st.num_drops = static_cast<int16_t>(st.drop_reasons.size());
  st.state_write_failures = static_cast<int64_t>(node_.stateWriteFailures());
  if (!robot_bus_(channels_.status, msg::encodeLcm(st))) spdlog::warn("{}: publish failed", channels_.status);
}

}  // namespace slide
