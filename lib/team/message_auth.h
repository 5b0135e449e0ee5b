#pragma once
// Authentication of team messages: HMAC-SHA256 with the team key over a canonical byte form
// of every field but the MAC, truncated to 16 bytes.
#include <string>

#include "team/messages.h"

namespace slide::team {

class MessageAuth {
 public:
  // `key`: the team key (any bytes); throws std::invalid_argument when empty.
  explicit MessageAuth(std::string key);

  void sign(Heartbeat& m) const { m.mac = macOf(canonical(m)); }
  void sign(Chunk& m) const { m.mac = macOf(canonical(m)); }
  void sign(Ack& m) const { m.mac = macOf(canonical(m)); }
  bool verify(const Heartbeat& m) const { return equal(m.mac, macOf(canonical(m))); }
  bool verify(const Chunk& m) const { return equal(m.mac, macOf(canonical(m))); }
  bool verify(const Ack& m) const { return equal(m.mac, macOf(canonical(m))); }

  static Bytes canonical(const Heartbeat& m);
  static Bytes canonical(const Chunk& m);
  static Bytes canonical(const Ack& m);

 private:
  Mac macOf(const Bytes& data) const;
  static bool equal(const Mac& a, const Mac& b);  // constant time
  std::string key_;
};

}  // namespace slide::team
