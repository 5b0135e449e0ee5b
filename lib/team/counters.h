#pragma once
// Replay protection state, persisted: the counter this robot stamps on its messages (strictly
// increasing across restarts: blocks are reserved on disk before use) and, per sender, the
// highest counter accepted. The file is rewritten atomically (temp file + rename).
#include <cstdint>
#include <map>
#include <string>

namespace slide::team {

class CounterStore {
 public:
  static constexpr std::int64_t kBlock = 1 << 16;

  // Loads `path` if it exists (empty path: in memory only); throws std::runtime_error naming the
  // file and line on a malformed file.
  explicit CounterStore(std::string path);

  std::int64_t nextOwn();  // reserves a new block on disk when needed
  // True (and remembered) when `counter` is above every counter accepted from `sender`.
  bool accept(std::int32_t sender, std::int64_t counter);
  std::int64_t lastAccepted(std::int32_t sender) const;
  void save();  // writes the file when something changed since the last save

 private:
  void write();
  std::string path_;
  std::int64_t own_ = 0;       // last counter used
  std::int64_t reserved_ = 0;  // counters up to this are reserved on disk
  std::map<std::int32_t, std::int64_t> accepted_;
  bool dirty_ = false;
};

}  // namespace slide::team
