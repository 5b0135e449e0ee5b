#pragma once
// One robot's peer-sync protocol engine: the observation database, per-peer bookmarks
// (what each peer is known to hold, what was sent to it and when), thinning of the robot's own
// observations before they go on the team bus, packing of consecutive bundles into one chunk,
// relay of third robots' bundles, map sharing, authentication, replay protection, rate
// limiting, traffic accounting and in-order exactly-once delivery. Pure logic: messages in and
// out as structs, time as microseconds; the daemon (or a simulated network) moves the messages.
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "app/channels.h"
#include "objects/keypose_bundle.h"
#include "team/bandwidth.h"
#include "team/bundle_pack.h"
#include "team/codec.h"
#include "team/counters.h"
#include "team/drop_reason.h"
#include "team/map_sharing.h"
#include "team/message_auth.h"
#include "team/observation_db.h"
#include "team/observation_thinning.h"
#include "team/rate_limiter.h"
#include "team/reassembly.h"
#include "team/shared_map.h"
#include "team/sync_config.h"

namespace slide::team {

struct TeamChannels {
  std::string heartbeat = app::channels::kTeamHeartbeat;
  std::string chunk = app::channels::kTeamChunk;
  std::string ack = app::channels::kTeamAck;
};

struct TickOutput {
  std::vector<Heartbeat> heartbeats;
  std::vector<Chunk> chunks;
  std::vector<Ack> acks;
  bool empty() const { return heartbeats.empty() && chunks.empty() && acks.empty(); }
};

class PeerSyncNode {
 public:
  // `state_dir` holds journal.bin and counters.txt (empty: memory only, nothing survives).
  // `wall_clock` stamps message counters and map versions (counters.h); `now` and every other
  // time argument may be any monotonic clock.
  PeerSyncNode(SyncConfig cfg, const std::string& state_dir, Micros now, TeamChannels channels = {},
               WallClock wall_clock = systemWallClock());
  ~PeerSyncNode();

  // The robot's own key-pose bundle; returns the reason when refused.
  std::optional<Drop> addOwnBundle(KeyPoseBundle b, Micros now);
  // The robot's current object map (its version is assigned here).
  void setOwnMap(SharedMap m, Micros now);

  void receive(const Heartbeat& m, Micros now);
  void receive(const Chunk& m, Micros now);
  void receive(const Ack& m, Micros now);
  // A team-bus message that could not even be decoded.
  void countMalformed() { ++drops_[static_cast<int>(Drop::Malformed)]; }

  // What to send now (signed); call often (e.g. every 50 ms).
  TickOutput tick(Micros now);

  // The next peer bundle to hand to the robot's own stack, in per-origin order; the same one
  // until confirmDelivered() records it in the journal. A held bundle that does not decode
  // with its predecessor's context is stepped over (journalled as passed) and counted as
  // Drop::Undeliverable; absent seqs are stepped over too.
  std::optional<KeyPoseBundle> nextDelivery();
  void confirmDelivered(std::int32_t origin, std::int32_t seq);
  // Peers' maps received since the last call (newest version per robot).
  std::vector<SharedMap> takeMaps();

  const SyncConfig& config() const { return cfg_; }
  const ObservationDb& db() const { return db_; }
  // The encoding of a held bundle as it goes on the team bus (own bundles thinned), or null.
  const Bytes* wirePayload(std::int32_t origin, std::int32_t seq) const;
  const DropCounts& drops() const { return drops_; }
  std::uint64_t dropped(Drop d) const { return drops_[static_cast<int>(d)]; }
  const BandwidthMeter& traffic() const { return traffic_; }
  bool inReach(std::int32_t peer, Micros now) const;
  // Landmarks in the latest map shared by `robot` (own map for this robot).
  std::size_t landmarks(std::int32_t robot) const;
  // One line per peer: rates, bytes per landmark and per metre.
  std::vector<std::string> trafficSummary(Micros now) const;
  void persist() { counters_.save(); }
  const CounterStore& counters() const { return counters_; }
  // Writes of the journal or counters.txt that failed (a full disk): an alarm, never fatal.
  std::uint64_t stateWriteFailures() const { return db_.journalFailures() + counters_.writeFailures(); }

 private:
  using Key = std::pair<std::int32_t, std::int32_t>;  // (origin, seq)
  struct Peer {
    bool heard_heartbeat = false;
    Micros last_heard = 0;
    Micros last_heartbeat = 0;          // when its latest heartbeat arrived
    OriginRanges known;                 // last heartbeat's holdings plus later acknowledgements
    std::map<Key, Micros> sent;         // last time it was sent to this peer (by anyone)
    std::map<Key, Micros> lacking_since;
    bool ack_pending = false;
    Micros ack_due = 0;
    std::set<std::int32_t> ack_origins;
    std::int32_t our_map = 0;  // version of our map its last heartbeat said it holds (0: none)
  };

  bool admit(std::int32_t sender, std::int64_t counter, bool mac_ok, std::size_t bytes);
  bool inTeam(std::int32_t robot) const;
  void somethingNew();  // a peer back in reach, or a gap: heartbeats at the normal period again
  bool lacksSome(std::int32_t origin) const;  // a gap in what is held of `origin`, or not its start
  void drop(Drop d) { ++drops_[static_cast<int>(d)]; }
  void scheduleAck(std::int32_t peer, std::int32_t origin, Micros now);
  void receiveBundleChunk(const Chunk& m, Micros now);
  void receiveBundle(const Chunk& m, std::int32_t seq, PackedBundle packed, Micros now);  // one of its pack
  void receiveMapChunk(const Chunk& m, Micros now);
  OriginRanges truncated(const OriginRanges& r, const std::set<std::int32_t>* only) const;
  OriginRanges announced() const;  // what heartbeats say is held (own bundles once sent)
  std::vector<std::int32_t> peersInReach(Micros now) const;
  enum class SendResult { Sent, TooLarge, RateLimited };
  // Splits a payload into signed chunks and queues them when the rate limit allows; counts
  // the bytes as sent to `reach`.
  SendResult sendPayload(ChunkKind kind, std::int32_t receiver, std::int32_t origin, std::int32_t seq,
                         const Bytes& payload, const std::vector<std::int32_t>& reach, Micros now, TickOutput& out);
  void sendMap(Micros now, TickOutput& out);
  void sendBundles(Micros now, TickOutput& out);
  void forgetKnown(Peer& p);
  // utime, odometry pose and sigma of a held bundle, once its chain back to a self-contained
  // encoding is held (cached).
  std::optional<BundleContext> contextOf(std::int32_t origin, std::int32_t seq) const;
  Bytes sharedEncoding(std::int32_t seq, const Bytes& full);
  std::size_t wireBytes(const Chunk& c) const { return lcmWireBytes(channels_.chunk, encodedSize(c)); }

  SyncConfig cfg_;
  TeamChannels channels_;
  MessageAuth auth_;
  CounterStore counters_;
  ObservationDb db_;
  ObservationThinning thinning_;
  std::map<std::int32_t, Bytes> own_shared_;  // own bundles as shared, by seq
  std::map<std::int32_t, Micros> own_added_at_;  // own bundles not sent yet: when they came
  mutable std::map<Key, BundleContext> contexts_;
  Reassembler reassembler_;
  RateLimiter limiter_;
  BandwidthMeter traffic_;
  DropCounts drops_{};
  std::map<std::int32_t, Peer> peers_;
  Micros next_heartbeat_;
  Micros heartbeat_interval_ = 0;
  std::optional<Micros> last_heartbeat_at_;
  bool news_ = false;  // since the last heartbeat
  Micros counters_saved_at_ = 0;

  MapSharing maps_;
  std::int32_t own_map_version_ = 0;
  std::int32_t map_sent_version_ = 0;
  Micros map_sent_at_ = 0;
  std::map<std::int32_t, SharedMap> new_maps_;  // received since the last takeMaps()
};

}  // namespace slide::team
