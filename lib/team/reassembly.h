#pragma once
// Splitting payloads into chunks and putting them back together. Partial payloads are keyed
// by (kind, origin, seq, num_chunks); they expire, and their total size is bounded: payload
// bytes plus kSlotBytes per part slot allocated, and no sender holds more than half of it.
#include <map>
#include <optional>
#include <tuple>

#include "team/drop_reason.h"
#include "team/messages.h"
#include "team/rate_limiter.h"

namespace slide::team {

// Pieces of at most `max_chunk` bytes (at least one piece, possibly empty).
std::vector<Bytes> splitPayload(const Bytes& data, std::size_t max_chunk);

class Reassembler {
 public:
  Reassembler(std::size_t max_bytes, Micros timeout) : max_bytes_(max_bytes), timeout_(timeout) {}

  // Adds a chunk (header already validated: 0 <= index < num_chunks). Returns the payload when
  // complete; sets `drop` when the chunk is refused.
  std::optional<Bytes> add(const Chunk& c, Micros now, std::optional<Drop>* drop);
  void expire(Micros now);
  std::size_t bytes() const { return bytes_; }
  static constexpr std::size_t kSlotBytes = sizeof(Bytes) + 1;

 private:
  using Key = std::tuple<int, std::int32_t, std::int32_t, int>;
  struct Partial {
    std::vector<Bytes> parts;
    std::vector<bool> have;
    int count = 0;
    std::size_t bytes = 0;
    Micros started = 0;
    std::int32_t sender = 0;  // who started it (its space is charged to it)
  };
  void erase(std::map<Key, Partial>::iterator it);
  std::size_t max_bytes_;
  Micros timeout_;
  std::size_t bytes_ = 0;
  std::map<Key, Partial> partial_;
  std::map<std::int32_t, std::size_t> by_sender_;
};

}  // namespace slide::team
