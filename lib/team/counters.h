#pragma once
// Replay protection state, persisted: the counter this robot stamps on its messages and, per
// sender, the highest counter accepted plus which of the kWindow counters below it were
// accepted, so that messages reordered in flight are still taken once (a window as in
// IPsec/DTLS). The file is rewritten atomically (temp file + rename).
//
// Counters are clock-based: a robot's next counter is max(last + 1, wall clock in µs), so it
// stays strictly increasing across restarts even when counters.txt is lost (its epoch is the
// clock; a block of kBlock µs ahead is reserved on disk before use, so a clock set back does
// not reuse counters either). A receiver accepts no counter beyond its own clock plus
// `max_ahead` µs (a counter from the future would otherwise lock the sender out until its
// clock got there), and forgets a persisted highest that lies beyond that. Only the highest is
// persisted: after a restart nothing at or below it is accepted.
//
// A damaged file does not stop a robot: a line that does not parse is skipped with a warning
// (warnings()); without its `own` line the robot goes on from the clock, as with the file lost,
// and a sender without its line is taken as new, as with the file lost. A failed write (a
// full disk) is counted (writeFailures), never thrown: counters go on from memory and the
// clock, and the file is written again at the next save.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace slide::team {

using WallClock = std::function<std::int64_t()>;  // µs since 1970
WallClock systemWallClock();

class CounterStore {
 public:
  static constexpr std::int64_t kBlock = 2000000;  // µs of counters reserved at a time
  static constexpr std::int64_t kWindow = 64;
  enum class Verdict { New, Replay, Future };

  // Loads `path` if it exists (empty path: in memory only); lines that do not parse are
  // skipped, each named by file and line in warnings(). `max_ahead`: µs a sender's counter may
  // lead `clock`.
  explicit CounterStore(std::string path, WallClock clock = systemWallClock(), std::int64_t max_ahead = 300000000);

  std::int64_t nextOwn();  // reserves a new block on disk when needed
  // New (and remembered) when `counter` is new from `sender`: above the highest accepted, or
  // within kWindow below it and not accepted before, and not beyond the clock plus max_ahead.
  Verdict check(std::int32_t sender, std::int64_t counter);
  bool accept(std::int32_t sender, std::int64_t counter) { return check(sender, counter) == Verdict::New; }
  std::int64_t lastAccepted(std::int32_t sender) const;
  void save();  // writes the file when something changed since the last save (or a write failed)
  const std::vector<std::string>& warnings() const { return warnings_; }
  std::uint64_t writeFailures() const { return write_failures_; }
  const std::string& lastWriteError() const { return write_error_; }

 private:
  void write();
  std::string path_;
  WallClock clock_;
  std::int64_t max_ahead_;
  std::int64_t own_ = 0;       // last counter used
  std::int64_t reserved_ = 0;  // counters up to this are reserved on disk
  struct Seen {
    std::int64_t highest = 0;
    std::uint64_t below = ~std::uint64_t{0};  // bit i: highest - 1 - i was accepted (or is too old to tell)
  };
  std::map<std::int32_t, Seen> accepted_;
  bool dirty_ = false;
  std::vector<std::string> warnings_;
  std::uint64_t write_failures_ = 0;
  std::string write_error_;
};

}  // namespace slide::team
