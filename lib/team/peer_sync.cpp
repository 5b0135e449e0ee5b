#include "team/peer_sync.h"

#include <algorithm>
#include <deque>
#include <stdexcept>

#include "team/bundle_pack.h"
#include "team/codec.h"

namespace slide::team {
namespace {

Micros secs(double s) { return static_cast<Micros>(s * 1e6); }
constexpr std::size_t kMaxChunkBytes = 32767;  // the team bus's int16 size

std::string joinPath(const std::string& dir, const char* name) {
  return dir.empty() ? std::string() : dir + "/" + name;
}

}  // namespace

PeerSyncNode::PeerSyncNode(SyncConfig cfg, const std::string& state_dir, Micros now, TeamChannels channels,
                           WallClock wall_clock)
    : cfg_((cfg.validate(), std::move(cfg))),
      channels_(std::move(channels)),
      auth_(cfg_.robot, cfg_.team, cfg_.pair_keys),
      counters_(joinPath(state_dir, "counters.txt"), std::move(wall_clock), secs(cfg_.max_counter_ahead_s)),
      db_(joinPath(state_dir, "journal.bin")),
      thinning_(cfg_.thinning()),
      reassembler_(cfg_.reassembly_bytes, secs(cfg_.reassembly_timeout_s)),
      limiter_(cfg_.rate_limit_bytes_per_s, cfg_.burst_bytes),
      traffic_(now),
      next_heartbeat_(now),
      maps_(MapSharingParams{cfg_.map_delta_move_m}) {
  // What was shared of the journalled own bundles: the same stream through the same policy.
  // One that does not decode (a journal of another encoding version) is not shared, and counted.
  // Own bundles that came back from peers keep the tags they came with: never signed here.
  auto own = db_.stored().find(cfg_.robot);
  if (own == db_.stored().end()) return;
  for (const SeqRange& r : own->second.ranges())
    for (std::int64_t seq = r.first; seq <= r.last; ++seq) {
      const auto s = static_cast<std::int32_t>(seq);
      if (db_.get(cfg_.robot, s)->received) continue;
      try {
        own_shared_[s] = sharedEncoding(s, db_.get(cfg_.robot, s)->data);
      } catch (const std::runtime_error&) {
        drop(Drop::Undeliverable);
      }
    }
}

// The thinning sees the bundle as decoded from its journalled encoding, so that replaying the
// journal gives the same decisions.
Bytes PeerSyncNode::sharedEncoding(std::int32_t seq, const Bytes& full) {
  const auto previous = contextOf(cfg_.robot, seq - 1);
  std::string error;
  const auto b = decodeBundle(full, cfg_.robot, seq, &error, previous ? &*previous : nullptr);
  if (!b)
    throw std::runtime_error("own bundle " + std::to_string(seq) + " does not decode: " + error);
  return encodeBundle(thinning_.thin(*b), previous ? &*previous : nullptr,
                      cfg_.thin_observations ? BundleDetail::Team : BundleDetail::Full);
}

const Bytes* PeerSyncNode::wirePayload(std::int32_t origin, std::int32_t seq) const {
  if (origin == cfg_.robot) {
    auto it = own_shared_.find(seq);
    if (it != own_shared_.end()) return &it->second;
  }  // (own bundles recovered from peers after losing the journal are held as shared)
  const ObservationDb::Entry* e = db_.get(origin, seq);
  return e ? &e->data : nullptr;
}


PeerSyncNode::~PeerSyncNode() {
  try {
    counters_.save();
  } catch (...) {
  }
}

void PeerSyncNode::somethingNew() {
  news_ = true;
  if (last_heartbeat_at_) next_heartbeat_ = std::min(next_heartbeat_, *last_heartbeat_at_ + secs(cfg_.heartbeat_period_s));
}

bool PeerSyncNode::lacksSome(std::int32_t origin) const {
  auto held = db_.held().find(origin);
  return held != db_.held().end() && (held->second.ranges().size() > 1 || !db_.firstSeq(origin));
}

bool PeerSyncNode::inTeam(std::int32_t robot) const {
  return std::find(cfg_.team.begin(), cfg_.team.end(), robot) != cfg_.team.end();
}

bool PeerSyncNode::inReach(std::int32_t peer, Micros now) const {
  auto it = peers_.find(peer);
  return it != peers_.end() && it->second.heard_heartbeat && now - it->second.last_heard <= secs(cfg_.peer_timeout_s);
}

std::vector<std::int32_t> PeerSyncNode::peersInReach(Micros now) const {
  std::vector<std::int32_t> out;
  for (const auto& [id, p] : peers_)
    if (inReach(id, now)) out.push_back(id);
  return out;
}

std::size_t PeerSyncNode::landmarks(std::int32_t robot) const {
  return maps_.landmarks(robot);
}

std::vector<std::string> PeerSyncNode::trafficSummary(Micros now) const {
  std::vector<std::string> lines;
  for (const auto& [id, t] : traffic_.peers()) lines.push_back(traffic_.summary(id, now, landmarks(id), db_.metres(id)));
  return lines;
}

// ---- own input ----

std::optional<Drop> PeerSyncNode::addOwnBundle(KeyPoseBundle b, Micros now) {
  if (b.robot != cfg_.robot) return drop(Drop::WrongOrigin), Drop::WrongOrigin;
  auto it = db_.held().find(cfg_.robot);
  const bool have_any = it != db_.held().end() && !it->second.empty();
  if (have_any) {
    const RangeSet& own = it->second;
    Drop d = Drop::kCount;
    const std::int64_t missing = std::int64_t{b.seq} - own.max() - 1;
    if (own.contains(b.seq)) d = Drop::Duplicate;
    else if (b.seq <= own.max()) d = Drop::SeqBackwards;
    else if (missing > cfg_.max_seq_jump) d = Drop::SeqJump;
    if (d != Drop::kCount) return drop(d), d;
    // Bundles lost on the robot bus: peers learn that they do not exist, delivery goes on.
    // The gap reaches back to the last bundle held: absences journalled here before a bundle
    // the journal then refused (a full disk) were never sent with it.
    if (missing > 0) {
      if (!db_.addAbsent(cfg_.robot, own.max() + 1, b.seq - 1)) return drop(Drop::JournalWrite), Drop::JournalWrite;
      drops_[static_cast<int>(Drop::Lost)] += static_cast<std::uint64_t>(missing);
    }
    const auto stored = db_.stored().find(cfg_.robot);
    b.gap = static_cast<std::int32_t>(stored == db_.stored().end() || stored->second.empty()
                                          ? missing
                                          : std::int64_t{b.seq} - stored->second.max() - 1);
  } else {
    b.gap = 0;
  }
  b.first = !have_any;
  const std::optional<BundleContext> previous = contextOf(b.robot, b.seq - 1);
  ObservationDb::Entry e;
  e.data = encodeBundle(b, previous ? &*previous : nullptr);  // journalled in full
  Bytes shared = sharedEncoding(b.seq, e.data);
  e.first = b.first;
  e.step_m = static_cast<float>(b.first ? 0.0 : b.relative_odom.translation().norm());
  // Not journalled (a full disk): not held either; the next one bridges the gap to it.
  if (!db_.add(b.robot, b.seq, std::move(e))) return drop(Drop::JournalWrite), Drop::JournalWrite;
  own_shared_[b.seq] = std::move(shared);
  own_added_at_[b.seq] = now;
  return std::nullopt;
}

void PeerSyncNode::setOwnMap(SharedMap m, Micros now) {
  m.robot = cfg_.robot;
  // Versions are the message counter's seconds since 2024 (counters.h), so they grow across
  // restarts, counters.txt lost or not, until 2092.
  constexpr std::int64_t k2024 = 1704067200LL * 1000000;
  const std::int64_t secs_since = (counters_.nextOwn() - k2024) / 1000000;
  own_map_version_ = static_cast<std::int32_t>(
      std::clamp<std::int64_t>(std::max<std::int64_t>(secs_since, std::int64_t{own_map_version_} + 1), 1, INT32_MAX));
  m.version = own_map_version_;
  maps_.setOwn(std::move(m));
}

// ---- team input ----

bool PeerSyncNode::admit(std::int32_t sender, std::int64_t counter, bool mac_ok, std::size_t bytes) {
  if (sender == cfg_.robot) return false;  // our own multicast echo
  if (!inTeam(sender)) return drop(Drop::UnknownSender), false;
  if (!mac_ok) return drop(Drop::BadMac), false;
  switch (counters_.check(sender, counter)) {
    case CounterStore::Verdict::Replay: return drop(Drop::Replay), false;
    case CounterStore::Verdict::Future: return drop(Drop::FutureCounter), false;
    case CounterStore::Verdict::New: break;
  }
  traffic_.received(sender, bytes);
  return true;
}

void PeerSyncNode::receive(const Heartbeat& m, Micros now) {
  if (m.sender == cfg_.robot) return;
  if (!admit(m.sender, m.counter, inTeam(m.sender) && auth_.verify(m),
             lcmWireBytes(channels_.heartbeat, encodedSize(m))))
    return;
  const bool was_in_reach = inReach(m.sender, now);
  Peer& p = peers_[m.sender];
  // Back in reach after a silence: relays wait relay_delay_s again, so the origin (or whoever
  // hears the peer too) gets the first chance and relays do not pile up on the same bundles.
  if (!was_in_reach) {
    p.lacking_since.clear();
    somethingNew();  // it needs our heartbeat to count us in reach
  }
  p.heard_heartbeat = true;
  p.last_heard = now;
  p.last_heartbeat = now;
  p.known = m.held;
  const auto ours = m.maps.find(cfg_.robot);
  p.our_map = ours == m.maps.end() ? 0 : ours->second;
  forgetKnown(p);
  // It holds something we lack (announced only once sent, so this is a loss or a relay to
  // come): our heartbeat should say so soon.
  static const RangeSet kNone;
  for (const auto& [origin, set] : m.held) {
    auto mine = db_.held().find(origin);
    if (!set.minus(mine == db_.held().end() ? kNone : mine->second, 1).empty()) {
      somethingNew();
      break;
    }
  }
}

void PeerSyncNode::receive(const Ack& m, Micros now) {
  if (m.sender == cfg_.robot) return;
  if (!admit(m.sender, m.counter, inTeam(m.sender) && auth_.verify(m), lcmWireBytes(channels_.ack, encodedSize(m))))
    return;
  Peer& p = peers_[m.sender];
  p.last_heard = now;
  insertAll(p.known, m.acked);  // what the acknowledging robot holds, whoever it told
  forgetKnown(p);
}

void PeerSyncNode::receive(const Chunk& m, Micros now) {
  if (m.sender == cfg_.robot) return;
  if (!admit(m.sender, m.counter, inTeam(m.sender) && auth_.verify(m), wireBytes(m))) return;
  peers_[m.sender].last_heard = now;
  if (m.num_chunks < 1 || m.chunk_index < 0 || m.chunk_index >= m.num_chunks || m.data.size() > kMaxChunkBytes ||
      m.seq < 0 || (m.kind != ChunkKind::Bundle && m.kind != ChunkKind::Map && m.kind != ChunkKind::MapDelta))
    return drop(Drop::Malformed);
  if (m.kind == ChunkKind::Bundle) receiveBundleChunk(m, now);
  else receiveMapChunk(m, now);
}

void PeerSyncNode::scheduleAck(std::int32_t peer, std::int32_t origin, Micros now) {
  Peer& p = peers_[peer];
  if (!p.ack_pending) {
    p.ack_pending = true;
    p.ack_due = now + secs(cfg_.ack_delay_s);
  }
  p.ack_origins.insert(origin);
}

void PeerSyncNode::receiveBundleChunk(const Chunk& m, Micros now) {
  if (!inTeam(m.origin)) return drop(Drop::UnknownOrigin);
  // The pack starts at m.seq: refuse it early when that is already implausible.
  const auto first = db_.firstSeq(m.origin);
  // (Own bundles from before the first held come back from peers after a lost journal.)
  if (first && m.seq < *first && m.origin != cfg_.robot) return drop(Drop::SeqBackwards);
  auto held = db_.held().find(m.origin);
  std::int64_t base = held != db_.held().end() && !held->second.empty() ? held->second.max() : -1;
  if (first) base = std::max<std::int64_t>(base, *first);
  if (base >= 0 && static_cast<std::int64_t>(m.seq) > base + cfg_.max_seq_jump) return drop(Drop::SeqJump);

  std::optional<Drop> refused;
  std::optional<Bytes> payload = reassembler_.add(m, now, &refused);
  if (refused) return drop(*refused);
  if (!payload) return;
  std::string error;
  auto bundles = unpackBundles(*payload, &error);
  if (!bundles || static_cast<std::int64_t>(m.seq) + static_cast<std::int64_t>(bundles->size()) - 1 > INT32_MAX)
    return drop(Drop::Malformed);
  for (std::size_t i = 0; i < bundles->size(); ++i)
    receiveBundle(m, static_cast<std::int32_t>(m.seq + static_cast<std::int64_t>(i)), std::move((*bundles)[i]), now);
}

void PeerSyncNode::receiveBundle(const Chunk& m, std::int32_t seq, PackedBundle packed, Micros now) {
  // The chunk's MAC proves its sender only: a relayed bundle needs its origin's tag for this
  // robot. An own bundle given back (this robot lost its journal) needs its tags as this robot
  // makes them, or, untagged, must be older than every own bundle made since: it is then held
  // but never sent on, so it vouches for nothing and blocks no new one.
  if (m.origin == cfg_.robot) {
    const bool older = !own_shared_.empty() && seq < own_shared_.begin()->first;
    if (packed.tags.empty() ? !older : !auth_.verifyBundle(m.origin, seq, packed.data, packed.tags))
      return drop(Drop::BadMac);
  } else if (m.sender != m.origin && !auth_.verifyBundle(m.origin, seq, packed.data, packed.tags)) {
    return drop(Drop::BadMac);
  }
  Bytes data = std::move(packed.data);
  const Key key{m.origin, seq};
  // Overheard or not, the addressees now have it: do not send it to them too.
  for (auto& [id, p] : peers_)
    if (id != m.sender && (m.receiver == -1 || m.receiver == id)) p.sent[key] = now;
  const bool for_me = m.receiver == -1 || m.receiver == cfg_.robot;
  if (db_.has(m.origin, seq) || db_.absent(m.origin, seq)) {
    if (for_me) scheduleAck(m.sender, m.origin, now);
    return drop(Drop::Duplicate);
  }
  const auto first = db_.firstSeq(m.origin);
  auto held = db_.held().find(m.origin);
  std::string error;
  // With its predecessor held (the usual, in-order case) the step is known: it counts towards
  // the metres travelled; otherwise only the structure is checked and the step counts 0.
  const auto previous = contextOf(m.origin, seq - 1);
  bool needs_previous = false;
  const auto bundle = decodeBundle(data, m.origin, seq, &error, previous ? &*previous : nullptr, &needs_previous);
  if (!bundle) return drop(Drop::Malformed);
  // A bundle claiming to start its origin's stream while earlier ones are held: its origin lost
  // its journal (and so its memory of them). It is a later bundle, not the start: taken as such,
  // so that the origin is not silenced.
  const bool starts = bundle->first && !(first && *first != seq) &&
                      !(held != db_.held().end() && !held->second.empty() && held->second.min() < seq);
  // A bundle after a gap: the gap's seqs do not exist, so none may be held or precede the first.
  if (bundle->gap > 0) {
    const SeqRange gap{static_cast<std::int32_t>(std::int64_t{seq} - bundle->gap), seq - 1};
    auto stored = db_.stored().find(m.origin);
    if (gap.first < 0 || (first && gap.first < *first) ||
        (stored != db_.stored().end() && stored->second.intersects(gap)))
      return drop(Drop::Malformed);
    // (Already absent when an earlier copy was cut short between the two journal records.)
    const std::uint64_t failures = db_.journalFailures();
    if (!db_.absentAll(m.origin, gap) && !db_.addAbsent(m.origin, gap.first, gap.last))
      return drop(db_.journalFailures() > failures ? Drop::JournalWrite : Drop::Malformed);
  }
  ObservationDb::Entry e;
  e.data = std::move(data);
  e.received = true;
  e.tags = std::move(packed.tags);
  e.first = starts;
  e.step_m = static_cast<float>(bundle->first || needs_previous ? 0.0 : bundle->relative_odom.translation().norm());
  if (!db_.add(m.origin, seq, std::move(e))) return drop(Drop::JournalWrite);  // not held: sent again
  // In order, the next heartbeat acknowledges it whenever it goes; a gap means a loss that only
  // our heartbeat gets resent.
  if (lacksSome(m.origin)) somethingNew();
  scheduleAck(m.sender, m.origin, now);
}

void PeerSyncNode::receiveMapChunk(const Chunk& m, Micros now) {
  if (m.origin != m.sender) return drop(Drop::WrongOrigin);
  if (m.seq <= maps_.heldVersion(m.origin)) return drop(Drop::Stale);  // before it takes reassembly space
  std::optional<Drop> refused;
  std::optional<Bytes> payload = reassembler_.add(m, now, &refused);
  if (refused) return drop(*refused);
  if (!payload) return;
  std::variant<SharedMap, Drop> got = maps_.receive(m.kind, m.origin, m.seq, *payload);
  if (const Drop* d = std::get_if<Drop>(&got)) {
    if (*d == Drop::MapBaseMissing) somethingNew();  // our next heartbeat tells which version we hold
    return drop(*d);
  }
  new_maps_[m.origin] = std::move(std::get<SharedMap>(got));
}

void PeerSyncNode::forgetKnown(Peer& p) {
  auto known = [&](const Key& k) {
    auto it = p.known.find(k.first);
    return it != p.known.end() && it->second.contains(k.second);
  };
  for (auto* m : {&p.sent, &p.lacking_since})
    for (auto it = m->begin(); it != m->end();) it = known(it->first) ? m->erase(it) : std::next(it);
}

// ---- output ----

OriginRanges PeerSyncNode::truncated(const OriginRanges& r, const std::set<std::int32_t>* only) const {
  OriginRanges out;
  for (const auto& [origin, set] : r) {
    if (only && !only->count(origin)) continue;
    auto ranges = set.ranges();
    if (ranges.size() > cfg_.max_ranges_per_origin) ranges.resize(cfg_.max_ranges_per_origin);
    out[origin] = RangeSet::fromRanges(ranges);
  }
  return out;
}

OriginRanges PeerSyncNode::announced() const {
  OriginRanges held = truncated(db_.held(), nullptr);
  // Own bundles still waiting for company have not gone out: peers could not have them.
  auto own = held.find(cfg_.robot);
  if (own != held.end() && !own_added_at_.empty()) {
    std::vector<SeqRange> sent;
    for (SeqRange r : own->second.ranges())
      if (r.first < own_added_at_.begin()->first) sent.push_back({r.first, std::min(r.last, own_added_at_.begin()->first - 1)});
    if (sent.empty()) held.erase(own);
    else own->second = RangeSet::fromRanges(sent);
  }
  return held;
}

TickOutput PeerSyncNode::tick(Micros now) {
  TickOutput out;
  reassembler_.expire(now);
  const bool heartbeat = now >= next_heartbeat_;
  if (heartbeat) {
    Heartbeat h;
    h.sender = cfg_.robot;
    h.counter = counters_.nextOwn();
    h.held = announced();
    h.maps = maps_.held();
    auth_.sign(h);
    const std::size_t bytes = lcmWireBytes(channels_.heartbeat, encodedSize(h));
    limiter_.force(static_cast<double>(bytes), now);
    traffic_.sent(peersInReach(now), bytes);
    out.heartbeats.push_back(std::move(h));
    // No news (a peer back in reach, a gap in what we hold): the next heartbeat waits twice as
    // long, up to heartbeat_idle_factor periods; somethingNew() pulls it back in. Peers learn
    // our own bundles and map from the chunks, and what arrived in order can wait to be
    // acknowledged (nothing is resent before a heartbeat says it is lacking).
    const Micros longest = secs(cfg_.heartbeat_period_s * cfg_.heartbeat_idle_factor);
    heartbeat_interval_ = news_ || heartbeat_interval_ == 0 ? secs(cfg_.heartbeat_period_s)
                                                            : std::min(2 * heartbeat_interval_, longest);
    news_ = false;
    last_heartbeat_at_ = now;
    next_heartbeat_ = now + heartbeat_interval_;
  }
  // Acknowledgements due: one message for every peer waiting (receiver -1 when several); a
  // heartbeat just sent says the same to everyone, so it acknowledges all.
  std::vector<std::int32_t> ack_to;
  std::set<std::int32_t> ack_origins;
  for (auto& [id, p] : peers_) {
    if (!p.ack_pending || (now < p.ack_due && !heartbeat)) continue;
    if (!heartbeat) {
      ack_to.push_back(id);
      ack_origins.insert(p.ack_origins.begin(), p.ack_origins.end());
    }
    p.ack_pending = false;
    p.ack_origins.clear();
  }
  if (!ack_to.empty()) {
    // Peers with an acknowledgement pending but not yet due ride along.
    for (auto& [id, p] : peers_) {
      if (!p.ack_pending) continue;
      ack_to.push_back(id);
      ack_origins.insert(p.ack_origins.begin(), p.ack_origins.end());
      p.ack_pending = false;
      p.ack_origins.clear();
    }
    Ack a;
    a.sender = cfg_.robot;
    a.receiver = ack_to.size() == 1 ? ack_to[0] : -1;
    a.counter = counters_.nextOwn();
    a.acked = truncated(db_.held(), &ack_origins);
    auth_.sign(a);
    const std::size_t bytes = lcmWireBytes(channels_.ack, encodedSize(a));
    limiter_.force(static_cast<double>(bytes), now);
    traffic_.sent(ack_to, bytes);
    out.acks.push_back(std::move(a));
  }
  sendMap(now, out);
  sendBundles(now, out);
  // Accepted counters reach the disk at most once a second: after a crash, messages accepted
  // in that last second could be accepted once more, which changes nothing (all idempotent).
  if (now - counters_saved_at_ >= secs(1.0)) {
    counters_.save();
    counters_saved_at_ = now;
  }
  return out;
}

PeerSyncNode::SendResult PeerSyncNode::sendPayload(ChunkKind kind, std::int32_t receiver, std::int32_t origin,
                                                   std::int32_t seq, const Bytes& payload,
                                                   const std::vector<std::int32_t>& reach, Micros now,
                                                   TickOutput& out) {
  const auto parts = splitPayload(payload, cfg_.max_chunk_bytes);
  if (parts.size() > 32767) return SendResult::TooLarge;
  std::vector<Chunk> chunks;
  std::size_t bytes = 0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    Chunk c;
    c.sender = cfg_.robot;
    c.receiver = receiver;
    c.kind = kind;
    c.origin = origin;
    c.seq = seq;
    c.chunk_index = static_cast<std::int16_t>(i);
    c.num_chunks = static_cast<std::int16_t>(parts.size());
    c.data = parts[i];
    c.mac.assign(MessageAuth::tagBytes(cfg_.team.size()), 0);  // (signed below, once the rate limit allows)
    bytes += wireBytes(c);
    chunks.push_back(std::move(c));
  }
  if (!limiter_.tryTake(static_cast<double>(bytes), now)) return SendResult::RateLimited;
  for (auto& c : chunks) {
    c.counter = counters_.nextOwn();
    auth_.sign(c);
    out.chunks.push_back(std::move(c));
  }
  traffic_.sent(reach, bytes);
  return SendResult::Sent;
}

void PeerSyncNode::sendMap(Micros now, TickOutput& out) {
  if (!maps_.own()) return;
  const auto reach = peersInReach(now);
  if (reach.empty()) return;
  // What each peer in reach said it holds of our map (0: none, or not said yet).
  std::vector<std::int32_t> held;
  for (std::int32_t id : reach) held.push_back(peers_[id].our_map);
  const bool everyone_current =
      std::all_of(held.begin(), held.end(), [&](std::int32_t v) { return v == own_map_version_; });
  const bool changed = own_map_version_ != map_sent_version_;
  const Micros since = now - map_sent_at_;
  if (!((changed && (map_sent_version_ == 0 || since >= secs(cfg_.map_period_s))) ||
        (!everyone_current && since >= secs(cfg_.map_refresh_s))))
    return;
  const std::optional<MapSharing::Outgoing> o = maps_.next(held);
  if (!o || sendPayload(o->kind, -1, cfg_.robot, o->version, o->payload, reach, now, out) != SendResult::Sent) return;
  maps_.sent(*o);
  map_sent_version_ = own_map_version_;
  map_sent_at_ = now;
}

void PeerSyncNode::sendBundles(Micros now, TickOutput& out) {
  const auto reach = peersInReach(now);
  if (reach.empty()) return;
  // Per origin, the bundles due to some peer in reach, with the peers they are due to.
  std::map<std::int32_t, std::map<std::int32_t, std::vector<std::int32_t>>> due;
  for (std::int32_t id : reach) {
    Peer& p = peers_[id];
    for (const auto& [origin, set] : db_.stored()) {  // (absent seqs travel as the gap of the bundle after them)
      static const RangeSet kNone;
      auto k = p.known.find(origin);
      const auto missing = set.minus(k == p.known.end() ? kNone : k->second, cfg_.max_sends_per_tick);
      // A third robot's bundle: its origin (or another holder) gets the first chance; whoever
      // still sees the peer lacking it after relay_delay_s relays it.
      const bool relay = origin != cfg_.robot && origin != id;
      // A robot holds its own bundles: only fill gaps below what it says it holds (it lost some).
      const bool own_to_origin = origin == id;
      const std::int32_t origin_max =
          own_to_origin && k != p.known.end() && !k->second.empty() ? k->second.max() : INT32_MIN;
      for (std::int32_t seq : missing) {
        if (own_to_origin && seq >= origin_max) break;
        // Another origin's bundle goes only where its tag block lets it be taken (its origin
        // takes it back untagged, see receiveBundle); an own one given back untagged
        // (unverified) goes nowhere.
        if (origin != cfg_.robot) {
          const ObservationDb::Entry* e = db_.get(origin, seq);
          if (!e || (!own_to_origin && !auth_.bundleTagged(origin, e->tags, id))) continue;
        } else if (!own_shared_.count(seq)) {
          const ObservationDb::Entry* e = db_.get(origin, seq);
          if (!e || e->tags.empty()) continue;
        }
        const Key key{origin, seq};
        const Micros lacking = p.lacking_since.emplace(key, now).first->second;
        if (relay && now - lacking < secs(cfg_.relay_delay_s)) continue;
        // Sent before: send again only when a heartbeat that left the peer well after our send
        // still lacks it (the send was lost), and not more often than resend_timeout_s. While
        // the link is down nothing is heard, so nothing is wasted on it.
        auto s = p.sent.find(key);
        if (s != p.sent.end() && (now - s->second < secs(cfg_.resend_timeout_s) ||
                                  p.last_heartbeat < s->second + secs(cfg_.loss_grace_s)))
          continue;
        due[origin][seq].push_back(id);
      }
    }
  }
  // Per origin, packs of consecutive bundles due to the same peers, each within one chunk (a
  // bundle larger than a chunk goes alone, in several).
  struct Pack {
    std::int32_t first;
    std::vector<const Bytes*> bundles, tags;
    std::vector<std::int32_t> to;
    std::size_t bytes;
    bool tagged;
  };
  std::deque<Bytes> own_tags;  // made for this send (stable addresses)
  std::vector<std::pair<std::int32_t, std::vector<Pack>>> packs;
  for (const auto& [origin, seqs] : due) {
    std::vector<Pack> list;
    for (const auto& [seq, to] : seqs) {
      const Bytes* data = wirePayload(origin, seq);
      if (!data) continue;
      const Bytes* tags = nullptr;
      if (origin == cfg_.robot && own_shared_.count(seq)) {
        // Tagged for the members it does not reach now (relays take it there); when sent
        // again (something was lost), for all.
        bool again = false;
        for (std::int32_t id : to) again = again || peers_[id].sent.count({origin, seq}) > 0;
        std::vector<std::int32_t> members;
        for (std::int32_t id : cfg_.team)
          if (again || std::find(to.begin(), to.end(), id) == to.end()) members.push_back(id);
        own_tags.push_back(auth_.bundleTags(seq, *data, members));
        if (!own_tags.back().empty()) tags = &own_tags.back();
      } else if (const ObservationDb::Entry* e = db_.get(origin, seq); e && !e->tags.empty()) {
        tags = &e->tags;  // as its origin made them
      }
      const std::size_t tag_bytes = tags ? tags->size() : 0;
      Pack* last = list.empty() ? nullptr : &list.back();
      const bool joins = last && last->to == to &&
                         last->first + static_cast<std::int64_t>(last->bundles.size()) == seq &&
                         last->bundles.size() < kMaxBundlesPerPack && last->bundles[0]->front() == data->front();
      const bool tagged = tag_bytes > 0 || (joins && last->tagged);
      // A pack turning tagged: a tag length (0) for each bundle already in it.
      const std::size_t add = packedSize(data->size(), tag_bytes, tagged) +
                              (joins && tagged && !last->tagged ? last->bundles.size() : 0);
      if (joins && last->bytes + add <= cfg_.max_chunk_bytes) {
        last->bundles.push_back(data);
        last->tags.push_back(tags);
        last->bytes += add;
        last->tagged = tagged;
      } else {
        list.push_back({seq, {data}, {tags}, to, 2 + packedSize(data->size(), tag_bytes, tag_bytes > 0), tag_bytes > 0});
      }
    }
    // Own new bundles wait up to bundle_hold_s for company (one chunk's worth at most).
    if (origin == cfg_.robot && list.size() == 1) {
      const Pack& only = list[0];
      bool fresh = true;
      for (std::size_t k = 0; k < only.bundles.size() && fresh; ++k)
        fresh = own_added_at_.count(only.first + static_cast<std::int32_t>(k)) > 0;
      if (fresh && now - own_added_at_.at(only.first) < secs(cfg_.bundle_hold_s)) continue;
    }
    packs.emplace_back(origin, std::move(list));
  }
  // Round robin over origins, each in sequence order, until the rate limit says stop.
  std::vector<std::size_t> next(packs.size(), 0);
  bool progress = true;
  while (progress) {
    progress = false;
    for (std::size_t i = 0; i < packs.size(); ++i) {
      const auto& [origin, list] = packs[i];
      if (next[i] == list.size()) continue;
      const Pack& pack = list[next[i]++];
      const SendResult r = sendPayload(ChunkKind::Bundle, pack.to.size() == 1 ? pack.to[0] : -1, origin, pack.first,
                                       packBundles(pack.bundles, pack.tags), pack.to, now, out);
      if (r == SendResult::TooLarge) continue;
      if (r == SendResult::RateLimited) return;
      for (std::size_t k = 0; k < pack.bundles.size(); ++k) {
        const std::int32_t seq = pack.first + static_cast<std::int32_t>(k);
        for (std::int32_t id : pack.to) peers_[id].sent[{origin, seq}] = now;
        if (origin == cfg_.robot) own_added_at_.erase(seq);
      }
      progress = true;
    }
  }
}

// ---- delivery ----

std::optional<BundleContext> PeerSyncNode::contextOf(std::int32_t origin, std::int32_t seq) const {
  std::vector<std::int32_t> todo;  // held, context not known yet: newest first
  std::optional<BundleContext> context;
  for (std::int64_t s = seq; s >= INT32_MIN; --s) {
    const Key key{origin, static_cast<std::int32_t>(s)};
    if (auto it = contexts_.find(key); it != contexts_.end()) {
      context = it->second;
      break;
    }
    const ObservationDb::Entry* e = db_.get(key.first, key.second);
    if (!e) return std::nullopt;
    todo.push_back(key.second);
    if (!chainedBundle(e->data)) break;
  }
  for (auto it = todo.rbegin(); it != todo.rend(); ++it) {
    std::string error;
    bool needs_previous = false;
    const Bytes& data = db_.get(origin, *it)->data;
    const auto b = decodeBundle(data, origin, *it, &error, context ? &*context : nullptr, &needs_previous);
    if (!b || needs_previous) return std::nullopt;
    context = BundleContext::of(*b, chainedBundle(data) ? &*context : nullptr);
    contexts_[{origin, *it}] = *context;
  }
  return context;
}

std::optional<KeyPoseBundle> PeerSyncNode::nextDelivery() {
  while (const auto next = db_.nextToDeliver(cfg_.robot)) {
    const auto [origin, seq] = *next;
    std::string error;
    // In per-origin order the previous bundle is held (delivered just before) unless absent.
    const std::optional<BundleContext> previous = contextOf(origin, seq - 1);
    bool needs_previous = false;
    auto b = decodeBundle(db_.get(origin, seq)->data, origin, seq, &error, previous ? &*previous : nullptr,
                          &needs_previous);
    if (b && !needs_previous) return b;
    // Held on the looser check (its predecessor was missing when it came) and unusable now:
    // stepped over for good (the cursor record is journalled), counted, never fatal.
    db_.markDelivered(origin, seq);
    drop(Drop::Undeliverable);
  }
  return std::nullopt;
}

void PeerSyncNode::confirmDelivered(std::int32_t origin, std::int32_t seq) { db_.markDelivered(origin, seq); }

std::vector<SharedMap> PeerSyncNode::takeMaps() {
  std::vector<SharedMap> out;
  for (auto& [id, m] : new_maps_) out.push_back(std::move(m));
  new_maps_.clear();
  return out;
}

}  // namespace slide::team
