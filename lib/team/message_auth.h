#pragma once
// Authentication of team messages with per-pair keys (team_keys.h): the sender writes one tag
// per other team member, in ascending id order, each the first kTagBytes of HMAC-SHA256 with
// the key of the pair {sender, member} over a canonical byte form of every field but the tags.
// A receiver checks its own tag only, so a team member can forge nothing another robot would
// accept as coming from a third (it lacks their pair's key). 64-bit tags: a forgery succeeds
// with probability 2^-64 per try.
//
// Bundles carry their origin's tags too (over origin, seq and encoding), which relays forward
// unchanged: a relayed bundle is taken only when its origin's tag for the receiver verifies,
// so a relay can pass bundles on but forge none (bundle_pack.h). An origin checks the bundles
// of its own that come back from peers (after it lost its journal) against all its tags.
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

  // This robot's tags, as origin, for its bundle `seq` encoded as `data`.
  Mac bundleTags(std::int32_t seq, const Bytes& data) const { return tags(canonicalBundle(robot_, seq, data)); }
  // Whether `tags` hold `origin`'s good tag for this robot over its bundle `seq`; for this
  // robot's own bundle (coming back from a peer), whether every tag is this robot's.
  bool verifyBundle(std::int32_t origin, std::int32_t seq, const Bytes& data, const Mac& tags) const;

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
  static bool equal(const std::uint8_t* a, const std::uint8_t* b, std::size_t n);  // constant time
  std::int32_t robot_;
  std::vector<std::int32_t> team_;  // sorted
  PairKeys keys_;
};

}  // namespace slide::team
