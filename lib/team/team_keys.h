#pragma once
// Per-robot team keys. Every pair of robots shares its own key, so a message carries one tag
// per team member (message_auth.h) and a robot can speak only for itself: it holds the keys of
// its own pairs, never the key another pair uses. A robot's key file lists the keys of its
// pairs and nothing else; it is read from disk (never from the command line) and must not be
// readable by other users:
//   # comment
//   robot 3                     (whose file this is)
//   peer 7 <64 hex digits>      (the key robot 3 shares with robot 7; one line per peer)
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace slide::team {

using PairKeys = std::map<std::int32_t, std::string>;  // peer id -> key shared with it (raw bytes)

// Throws std::runtime_error naming the file (and line) when it cannot be read, is readable by
// others, belongs to another robot, or has a malformed line or a key shorter than 16 bytes.
PairKeys loadTeamKeys(const std::string& path, std::int32_t robot);
// Writes `robot`'s key file with mode 0600 (throws std::runtime_error naming the path).
void writeTeamKeys(const std::string& path, std::int32_t robot, const PairKeys& keys);

// 32 random bytes (OpenSSL RAND_bytes) for a new pair.
std::string randomPairKey();
// The key of pair {a, b} derived from a master secret: HMAC-SHA256(master, "slide-pair lo hi").
// For simulations and tests, and for provisioning from one secret kept off the robots.
std::string derivePairKey(const std::string& master, std::int32_t a, std::int32_t b);
PairKeys derivePairKeys(const std::string& master, std::int32_t robot, const std::vector<std::int32_t>& team);

}  // namespace slide::team
