// slide-peer-sync: wires the peer-sync engine (lib/team) to the robot bus and the team bus.
#include <spdlog/spdlog.h>
#include <sys/select.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>

#include "app/app.h"
#include "msg/inbox.h"
#include "team/peer_sync.h"
#include "slide/peer_sync_status_t.hpp"
#include "team_msg.h"

using namespace slide;
using namespace slide::team;

namespace {

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

Micros nowMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// A team frame holds at most 32767 payload bytes (sync_chunk_t) or 32767 origins of a few
// ranges each (heartbeat, ack); anything longer is not a frame of ours.
constexpr std::size_t kMaxTeamFrameBytes = 1u << 20;

struct Channels {
  std::string own_bundle, own_map, peer_bundle, peer_map, status;
  TeamChannels team;
};

class PeerSyncDaemon {
 public:
  PeerSyncDaemon(PeerSyncNode& node, lcm::LCM& robot_bus, lcm::LCM& team_bus, Channels ch, int max_deliveries)
      : node_(node),
        robot_(robot_bus),
        team_(team_bus),
        robot_inbox_(robot_bus),
        team_inbox_(team_bus, kMaxTeamFrameBytes),
        ch_(std::move(ch)),
        max_deliveries_(max_deliveries) {
    // Raw subscriptions: the hardened decoders (cmake/lcm_gen_checked.cmake) run on bytes
    // already capped in size; a team frame's payload is decoded only after its MAC passed.
    robot_inbox_.subscribeRaw(ch_.own_bundle, &PeerSyncDaemon::onOwnBundle, this);
    robot_inbox_.subscribeRaw(ch_.own_map, &PeerSyncDaemon::onOwnMap, this);
    team_inbox_.subscribeRaw(ch_.team.heartbeat, &PeerSyncDaemon::onTeam<sync_heartbeat_t>, this);
    team_inbox_.subscribeRaw(ch_.team.chunk, &PeerSyncDaemon::onTeam<sync_chunk_t>, this);
    team_inbox_.subscribeRaw(ch_.team.ack, &PeerSyncDaemon::onTeam<sync_ack_t>, this);
  }

  void onOwnBundle(const lcm::ReceiveBuffer* rb, const std::string& channel) {
    std::string why = "undecodable keypose_bundle_t";
    auto m = decodeLcm<keypose_bundle_t>(rb->data, rb->data_size);
    std::optional<Bundle> b = m ? fromLcm(*m, &why) : std::nullopt;
    if (!b) return robot_inbox_.countUndecodable(channel, why);
    const std::uint64_t lost = node_.dropped(Drop::Lost);
    if (auto drop = node_.addOwnBundle(std::move(*b), nowMicros()))
      spdlog::warn("{}: dropped own bundle {}/{}: {}", channel, m->header.robot, m->header.seq, dropName(*drop));
    else if (node_.dropped(Drop::Lost) > lost)
      spdlog::warn("{}: own bundles {}..{} never arrived: peers learn the gap with bundle {}", channel,
                   m->header.seq - static_cast<std::int64_t>(node_.dropped(Drop::Lost) - lost), m->header.seq - 1,
                   m->header.seq);
  }

  void onOwnMap(const lcm::ReceiveBuffer* rb, const std::string& channel) {
    std::string why = "undecodable object_map_t";
    auto m = decodeLcm<object_map_t>(rb->data, rb->data_size);
    std::optional<SharedMap> map = m ? fromLcm(*m, &why) : std::nullopt;
    if (!map) return robot_inbox_.countUndecodable(channel, why);
    node_.setOwnMap(std::move(*map), nowMicros());
  }

  template <typename L>
  void onTeam(const lcm::ReceiveBuffer* rb, const std::string& channel) {
    std::string why = "undecodable message";
    auto m = decodeLcm<L>(rb->data, rb->data_size);
    auto msg = m ? fromLcm(*m, &why) : std::nullopt;
    if (!msg) {
      node_.countMalformed();
      return spdlog::debug("{}: dropped malformed message: {}", channel, why);
    }
    node_.receive(*msg, nowMicros());
  }

  void step() {
    const Micros now = nowMicros();
    TickOutput out = node_.tick(now);
    for (const auto& h : out.heartbeats) publish(ch_.team.heartbeat, toLcm(h));
    for (const auto& a : out.acks) publish(ch_.team.ack, toLcm(a));
    for (const auto& c : out.chunks) publish(ch_.team.chunk, toLcm(c));
    // Paced: a burst (after a link comes back) must not overrun the subscribers' UDP buffers.
    for (int k = 0; k < max_deliveries_; ++k) {
      auto b = node_.nextDelivery();
      if (!b) break;
      const keypose_bundle_t m = toLcm(*b);
      if (robot_.publish(ch_.peer_bundle, &m) != 0) {  // not recorded: tried again next step
        spdlog::warn("{}: publish of bundle {}/{} failed", ch_.peer_bundle, b->origin, b->seq);
        break;
      }
      node_.confirmDelivered(b->origin, b->seq);
      spdlog::debug("delivered bundle {}/{}", b->origin, b->seq);
    }
    for (const auto& map : node_.takeMaps()) {
      const object_map_t m = toLcm(map);
      robot_.publish(ch_.peer_map, &m);
      spdlog::info("map of robot {} ({} objects) delivered", map.robot, map.objects.size());
    }
    alarmOnWriteFailures();
  }

  // A full disk is an alarm, not a crash: an error at the first failed write and every 10 s
  // while more fail; the count goes out in every status.
  void alarmOnWriteFailures() {
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

  void logStats() {
    const Micros now = nowMicros();
    std::string drops;
    for (int d = 0; d < static_cast<int>(Drop::kCount); ++d)
      if (node_.drops()[d]) drops += fmt::format(" {}={}", dropName(static_cast<Drop>(d)), node_.drops()[d]);
    spdlog::info("held {} bundles, sent {:.0f} B, received {:.0f} B; drops:{}", node_.db().size(),
                 node_.traffic().totalSent(), node_.traffic().totalReceived(), drops.empty() ? " none" : drops);
    for (const msg::Inbox* inbox : {&robot_inbox_, &team_inbox_})
      if (inbox->dropped()) spdlog::info("dropped before decoding: {}", inbox->summary());
    for (const auto& line : node_.trafficSummary(now)) spdlog::info("{}", line);
    // The same counts for whoever watches the robot bus.
    peer_sync_status_t st;
    st.utime = std::chrono::duration_cast<std::chrono::microseconds>(
                   std::chrono::system_clock::now().time_since_epoch()).count();
    st.robot = node_.config().robot;
    st.held_bundles = static_cast<int32_t>(node_.db().size());
    st.bytes_sent = node_.traffic().totalSent();
    st.bytes_received = node_.traffic().totalReceived();
    for (int d = 0; d < static_cast<int>(Drop::kCount); ++d) {
      st.drop_reasons.push_back(dropName(static_cast<Drop>(d)));
      st.drop_counts.push_back(static_cast<int64_t>(node_.drops()[d]));
    }
    st.num_drops = static_cast<int16_t>(st.drop_reasons.size());
    st.state_write_failures = static_cast<int64_t>(node_.stateWriteFailures());
    if (robot_.publish(ch_.status, &st) != 0) spdlog::warn("{}: publish failed", ch_.status);
  }

 private:
  template <typename M>
  void publish(const std::string& channel, const M& m) {
    if (team_.publish(channel, &m) != 0) spdlog::warn("{}: publish failed", channel);
  }
  PeerSyncNode& node_;
  lcm::LCM& robot_;
  lcm::LCM& team_;
  msg::Inbox robot_inbox_, team_inbox_;
  Channels ch_;
  int max_deliveries_;
  std::uint64_t alarmed_failures_ = 0;
  std::chrono::steady_clock::time_point last_alarm_{};
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Peer-sync bookmark service: exchanges key-pose bundles and maps with teammates over the team bus, "
               "journals them, and delivers peers' bundles exactly once and in order on the robot bus."};
  CommonOptions common;
  addCommonOptions(app, common);
  std::string config_path = std::string(SLIDE_SOURCE_DIR) + "/config/peer_sync.yaml";
  std::int32_t robot = 0;
  std::string state_dir, robot_url, team_url, team_key_file;
  double run_for_s = 0;
  app.add_option("--config", config_path, "Peer-sync configuration (YAML; or a shared file with a peer_sync section)")
      ->capture_default_str();
  app.add_option("--robot", robot, "This robot's id (must be in the config's team list)")->required();
  app.add_option("--state-dir", state_dir, "Folder for journal and counters (default: config state_dir/robot<id>; without one /var/lib/slide/peer-sync/robot<id> as root, else $XDG_STATE_HOME/slide/... or ~/.local/state/slide/...)");
  app.add_option("--robot-url,--lcm-url", robot_url, "LCM URL of the robot bus (default: config robot_url)");
  app.add_option("--team-url", team_url, "LCM URL of the team bus (default: config team_url)");
  app.add_option("--team-key-file", team_key_file,
                 "This robot's team key file: the keys it shares with each peer, mode 0600, made by slide-team-keys "
                 "(default: config team_key_file; {robot} stands for the id)");
  app.add_option("--run-for", run_for_s, "Exit after this many seconds (0: until SIGINT/SIGTERM)");

  return runApp(app, common, argc, argv, [&]() {
    // Either a peer-sync file, or a shared file with a `peer_sync:` section.
    const ConfigNode root = ConfigNode::load(config_path);
    const ConfigNode cfg = root.has("peer_sync") ? root.child("peer_sync") : root;
    SyncConfig sync = SyncConfig::fromConfig(cfg, robot);
    sync.loadKeys(team_key_file);
    const ConfigNode chn = cfg.child("channels");
    Channels ch;
    ch.own_bundle = chn.get<std::string>("own_bundle");
    ch.own_map = chn.get<std::string>("own_map");
    ch.peer_bundle = chn.get<std::string>("peer_bundle");
    ch.peer_map = chn.get<std::string>("peer_map");
    ch.status = chn.get<std::string>("status", "PEER_SYNC_STATUS");
    ch.team.heartbeat = chn.get<std::string>("heartbeat");
    ch.team.chunk = chn.get<std::string>("chunk");
    ch.team.ack = chn.get<std::string>("ack");
    if (robot_url.empty()) robot_url = cfg.get<std::string>("robot_url", robotBusUrl(robot));
    if (team_url.empty()) team_url = cfg.get<std::string>("team_url");
    if (state_dir.empty()) {
      std::string base = cfg.get<std::string>("state_dir", "");
      if (base.empty()) base = persistentStateDir() + "/peer-sync";
      state_dir = base + "/robot" + std::to_string(robot);
    }
    const double tick_s = cfg.get<double>("tick_period_s", 0.05);
    const double stats_s = cfg.get<double>("stats_period_s", 10.0);
    const int max_deliveries = cfg.get<int>("max_deliveries_per_tick", 4);
    if (max_deliveries < 1) cfg.fail("max_deliveries_per_tick", "must be at least 1");
    if (!(tick_s > 0) || !(stats_s > 0)) cfg.fail("tick_period_s", "tick_period_s and stats_period_s must be positive");
    cfg.known({"robot", "robot_url", "team_url", "state_dir"});  // read above unless the command line set them
    cfg.rejectUnknownKeys();  // this file, or its peer_sync section of a shared file
    std::filesystem::create_directories(state_dir);

    lcm::LCM robot_bus(robot_url), team_bus(team_url);
    if (!robot_bus.good()) throw std::runtime_error("cannot open robot bus " + robot_url);
    if (!team_bus.good()) throw std::runtime_error("cannot open team bus " + team_url);
    PeerSyncNode node(sync, state_dir, nowMicros(), ch.team);
    for (const auto& w : node.counters().warnings()) spdlog::warn("robot {}: {}", robot, w);
    const auto& rec = node.db().recovery();
    if (rec.skipped)
      spdlog::warn("robot {}: journal {}: skipped {} records it cannot use (first: {})", robot, state_dir, rec.skipped,
                   rec.first_skipped);
    spdlog::info("robot {}: journal {} holds {} bundles ({} records){}", robot, state_dir, node.db().size(), rec.records,
                 rec.dropped_bytes ? fmt::format(", cut a damaged tail of {} bytes ({})", rec.dropped_bytes,
                                                 rec.not_saved.empty() ? "saved to " + rec.damaged_copy : rec.not_saved)
                                   : std::string());
    spdlog::info("robot {}: robot bus {}, team bus {}", robot, robot_url, team_url);
    PeerSyncDaemon daemon(node, robot_bus, team_bus, ch, max_deliveries);
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);

    const Micros start = nowMicros(), tick = static_cast<Micros>(tick_s * 1e6), stats = static_cast<Micros>(stats_s * 1e6);
    Micros next_tick = start, next_stats = start + stats;
    while (!g_stop && (run_for_s <= 0 || nowMicros() - start < static_cast<Micros>(run_for_s * 1e6))) {
      const Micros wait = std::max<Micros>(0, next_tick - nowMicros());
      fd_set fds;
      FD_ZERO(&fds);
      const int rfd = robot_bus.getFileno(), tfd = team_bus.getFileno();
      FD_SET(rfd, &fds);
      FD_SET(tfd, &fds);
      timeval tv{static_cast<time_t>(wait / 1000000), static_cast<suseconds_t>(wait % 1000000)};
      const int n = select(std::max(rfd, tfd) + 1, &fds, nullptr, nullptr, &tv);
      if (n > 0 && FD_ISSET(rfd, &fds)) robot_bus.handle();
      if (n > 0 && FD_ISSET(tfd, &fds)) team_bus.handle();
      const Micros now = nowMicros();
      if (now >= next_tick) {
        daemon.step();
        next_tick = now + tick;
      }
      if (now >= next_stats) {
        daemon.logStats();
        next_stats = now + stats;
      }
    }
    daemon.step();
    daemon.logStats();
    node.persist();
    spdlog::info("robot {}: stopped", robot);
    return 0;
  });
}
