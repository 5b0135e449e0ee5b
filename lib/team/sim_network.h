#pragma once
// A deterministic in-process team network for property tests and the benchmark: several
// PeerSyncNodes exchange messages over a shared medium (every message reaches every other
// robot whose link is up, as multicast does) with seeded loss, duplication, delay jitter
// (reordering), link cuts and restarts of any node from its state directory.
#include <functional>
#include <memory>
#include <queue>
#include <random>
#include <variant>

#include "team/peer_sync.h"

namespace slide::team {

struct SimLinkModel {
  double loss = 0;          // probability a copy is lost
  double duplicate = 0;     // probability a copy arrives twice
  double latency_s = 0.005;
  double jitter_s = 0;      // extra uniform delay: reorders messages
  // Whether robots a and b can hear each other at time t (default: always).
  std::function<bool(std::int32_t a, std::int32_t b, Micros t)> link_up;
};

using TeamMessage = std::variant<Heartbeat, Chunk, Ack>;

class SimNetwork {
 public:
  // One node per config; state lives under state_root/robot<id> (empty root: memory only,
  // restarts then lose everything, so only use restarts with a root).
  SimNetwork(std::vector<SyncConfig> configs, std::string state_root, SimLinkModel link, std::uint64_t seed);

  std::size_t size() const { return nodes_.size(); }
  PeerSyncNode& node(std::size_t i) { return *nodes_[i]; }
  Micros now() const { return now_; }

  // Advances time by `dt` in steps of `tick`: delivers due messages, ticks every node,
  // collects deliveries, puts outputs on the medium.
  void run(Micros dt, Micros tick = 50000);
  // Destroys node i and builds it again from its state directory (a kill -9 between ticks).
  void restart(std::size_t i);
  // Sets node i's wall clock this far from the simulated time (a clock set wrong).
  void setClockOffset(std::size_t i, Micros offset) { clock_offset_[i] = offset; }
  static constexpr Micros kSimEpoch = 1767225600LL * 1000000;  // 2026-01-01, µs
  // Puts a message on the medium as if robot `from_index` had sent it (for attack tests).
  void inject(std::size_t from_index, const TeamMessage& m);

  // Every bundle each node handed to its robot, in order, as (origin, seq).
  const std::vector<std::pair<std::int32_t, std::int32_t>>& delivered(std::size_t i) const { return delivered_[i]; }
  const std::vector<KeyPoseBundle>& deliveredBundles(std::size_t i) const { return delivered_bundles_[i]; }
  // Bytes put on the medium (each transmission counted once, LCM framing included).
  double bytesSent() const { return bytes_sent_; }
  std::size_t messagesSent() const { return messages_sent_; }
  // Observes every transmitted message (before loss).
  std::function<void(std::size_t from_index, const TeamMessage&)> on_send;

 private:
  struct InFlight {
    Micros at;
    std::uint64_t order;
    std::size_t to;
    TeamMessage msg;
    bool operator>(const InFlight& o) const { return at != o.at ? at > o.at : order > o.order; }
  };
  void transmit(std::size_t from, const TeamMessage& m);
  void makeNode(std::size_t i);
  std::size_t wireBytes(const TeamMessage& m) const;

  std::vector<SyncConfig> configs_;
  std::string state_root_;
  SimLinkModel link_;
  std::mt19937_64 rng_;
  Micros now_ = 0;
  std::uint64_t order_ = 0;
  std::vector<std::unique_ptr<PeerSyncNode>> nodes_;
  std::vector<Micros> clock_offset_;
  std::priority_queue<InFlight, std::vector<InFlight>, std::greater<InFlight>> medium_;
  std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>> delivered_;
  std::vector<std::vector<KeyPoseBundle>> delivered_bundles_;
  TeamChannels channels_;
  double bytes_sent_ = 0;
  std::size_t messages_sent_ = 0;
};

}  // namespace slide::team
