#pragma once
// Authentication of team messages with per-pair keys (team_keys.h): the sender writes one tag
// per other team member, in ascending id order, each the first kTagBytes of HMAC-SHA256 with
// the key of the pair {sender, member} over a canonical byte form of every field but the tags.
// A receiver checks its own tag only, so a team member can forge nothing another robot would
// accept as coming from a third (it lacks their pair's key). 64-bit tags: a forgery succeeds
// with probability 2^-64 per try.
//
// A bundle can carry its origin's tags too (over origin, seq and encoding), which relays
// forward unchanged: a relayed bundle is taken only when its origin's tag for the receiver
// verifies, so a relay can pass bundles on but forge none (bundle_pack.h). A tag block holds
// a u16 bitmap over the members other than the origin (ascending ids) and a tag per set bit;
// the origin tags a bundle for the members it does not reach directly (for all when it sends
// again), so bundles that need no relay carry no tags. An origin checks the bundles of its own
// that come back from peers (after it lost its journal) against its own tags.
#include <string>
#include <vector>

#include "team/messages.h"
#include "team/team_keys.h"

namespace slide::team {

class MessageAuth {
 public:
  static constexpr std::size_t kTagBytes = 8;
  static constexpr std::size_t kMaxTeam = 16;  // tags fit the int8 length on the wire

  // `keys`: the keys `robot` shares with every other member of `team`; throws
  // std::invalid_argument naming a member without a key (or an empty key), or a team too large.
  MessageAuth(std::int32_t robot, std::vector<std::int32_t> team, PairKeys keys);

  // Sign messages sent by this robot (m.sender must be it).
  void sign(Heartbeat& m) const { m.mac = tags(canonical(m)); }
  void sign(Chunk& m) const { m.mac = tags(canonical(m)); }
  void sign(Ack& m) const { m.mac = tags(canonical(m)); }
  // Check this robot's tag in a message from another member.
  bool verify(const Heartbeat& m) const { return check(m.sender, canonical(m), m.mac); }
  bool verify(const Chunk& m) const { return check(m.sender, canonical(m), m.mac); }
  bool verify(const Ack& m) const { return check(m.sender, canonical(m), m.mac); }

  // This robot's tag block, as origin, for its bundle `seq` encoded as `data`, with a tag for
  // each of `members` (other team members; others ignored); empty when there is none.
  Bytes bundleTags(std::int32_t seq, const Bytes& data, const std::vector<std::int32_t>& members) const;
  Bytes bundleTags(std::int32_t seq, const Bytes& data) const { return bundleTags(seq, data, team_); }  // for all
  // Whether the tag block holds a tag of `origin` for `member`.
  bool bundleTagged(std::int32_t origin, const Bytes& block, std::int32_t member) const;
  // Whether the tag block holds `origin`'s good tag for this robot over its bundle `seq`; for
  // this robot's own bundle (coming back from a peer), whether it holds tags and all are right.
  bool verifyBundle(std::int32_t origin, std::int32_t seq, const Bytes& data, const Bytes& block) const;

  static Bytes canonical(const Heartbeat& m);
  static Bytes canonicalBundle(std::int32_t origin, std::int32_t seq, const Bytes& data);
  static Bytes canonical(const Chunk& m);
  static Bytes canonical(const Ack& m);
  // Tag bytes a message of a team of `n` robots carries.
  static std::size_t tagBytes(std::size_t n) { return n > 0 ? kTagBytes * (n - 1) : 0; }

  Mac tags(const Bytes& data) const;
  bool check(std::int32_t sender, const Bytes& data, const Mac& mac) const;

 private:
  Mac tag(const std::string& key, const Bytes& data) const;
  int slotOf(std::int32_t origin, std::int32_t member) const;  // bit of `member` in origin's blocks, or -1
  static bool equal(const std::uint8_t* a, const std::uint8_t* b, std::size_t n);  // constant time
  std::int32_t robot_;
  std::vector<std::int32_t> team_;  // sorted
  PairKeys keys_;
};

}  // namespace slide::team
