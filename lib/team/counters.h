#pragma once
// Replay protection state, persisted: the counter this robot stamps on its messages (strictly
// increasing across restarts: blocks are reserved on disk before use) and, per sender, the
// highest counter accepted plus which of the kWindow counters below it were accepted, so that
// messages reordered in flight are still taken once (a window as in IPsec/DTLS). Only the
// highest is persisted: after a restart nothing at or below it is accepted. The file is
// rewritten atomically (temp file + rename).
#include <cstdint>
#include <map>
#include <string>

namespace slide::team {

class CounterStore {
 public:
  static constexpr std::int64_t kBlock = 1 << 16;
  static constexpr std::int64_t kWindow = 64;

  // Loads `path` if it exists (empty path: in memory only); throws std::runtime_error naming the
  // file and line on a malformed file.
  explicit CounterStore(std::string path);

  std::int64_t nextOwn();  // reserves a new block on disk when needed
  // True (and remembered) when `counter` is new from `sender`: above the highest accepted, or
  // within kWindow below it and not accepted before.
  bool accept(std::int32_t sender, std::int64_t counter);
  std::int64_t lastAccepted(std::int32_t sender) const;
  void save();  // writes the file when something changed since the last save

 private:
  void write();
  std::string path_;
  std::int64_t own_ = 0;       // last counter used
  std::int64_t reserved_ = 0;  // counters up to this are reserved on disk
  struct Seen {
    std::int64_t highest = 0;
    std::uint64_t below = ~std::uint64_t{0};  // bit i: highest - 1 - i was accepted (or is too old to tell)
  };
  std::map<std::int32_t, Seen> accepted_;
  bool dirty_ = false;
};

}  // namespace slide::team
