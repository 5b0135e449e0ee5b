#pragma once
// Why an input was dropped; every drop is counted under one of these.
#include <array>
#include <cstdint>

namespace slide::team {

enum class Drop : int {
  UnknownSender,   // sender not in the team list
  BadMac,          // wrong key, forged or tampered
  Replay,          // counter already accepted from that sender, or older than its window
  Malformed,       // undecodable LCM bytes, inconsistent chunk header or payload
  UnknownOrigin,   // bundle of a robot not in the team
  WrongOrigin,     // own-bundle input not from this robot, map not from its sender
  SeqBackwards,    // own input going back, or before the origin's first bundle
  SeqJump,         // sequence number jumping ahead
  Duplicate,       // already held (normal under loss and relay; counted, harmless)
  Stale,           // map older than the one held
  Overflow,        // reassembly space exhausted
  Lost,            // own bundles that never reached peer sync (counted per bundle; the gap is bridged)
  FutureCounter,   // counter beyond the local clock plus max_counter_ahead_s (not accepted, locks nobody out)
  Undeliverable,   // a held bundle that does not decode with its predecessor: skipped at delivery
  JournalWrite,    // not taken: the journal could not be written (a full disk); peers send it again
  MapBaseMissing,  // map changes against a version not held (the next heartbeat says which is)
  kCount
};

inline const char* dropName(Drop d) {
  static constexpr std::array<const char*, static_cast<int>(Drop::kCount)> names = {
      "unknown_sender", "bad_mac",  "replay",    "malformed", "unknown_origin", "wrong_origin",
      "seq_backwards",  "seq_jump", "duplicate", "stale",     "overflow",       "lost",
      "future_counter", "undeliverable",  "journal_write", "map_base_missing"};
  return names[static_cast<int>(d)];
}

using DropCounts = std::array<std::uint64_t, static_cast<int>(Drop::kCount)>;

}  // namespace slide::team
