#pragma once
// LCM event logs (the files lcm-logger writes and lcm-logplayer reads), read and written without
// LCM. An event is: sync word 0xEDA1DA01, event number (int64), timestamp in microseconds
// (int64), channel length (int32), data length (int32), channel, data; all big-endian.
// The reader is incremental: at a truncated tail (a log still being written) it stops before
// the incomplete event and picks up from there when called again after the file grew, so one
// reader can follow a live log. Corrupt input never throws: an event with an absurd channel or
// data length, or bytes that are no event, are skipped up to the next sync word and counted.
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace slide::io {

struct LcmLogEvent {
  std::int64_t event_number = 0;
  std::int64_t utime = 0;  // when the logger received it, microseconds since the epoch
  std::string channel;
  std::vector<std::uint8_t> data;
};

struct LcmLogCounts {
  std::uint64_t events = 0;        // events returned
  std::uint64_t skipped = 0;       // events not wanted (their data was not read)
  std::uint64_t corrupt = 0;       // bad lengths or lost sync (each resync counts once)
  std::uint64_t corrupt_bytes = 0; // bytes passed over to find the next sync word
};

class LcmLogReader {
 public:
  static constexpr std::int32_t kMaxChannelBytes = 256;
  static constexpr std::int32_t kMaxDataBytes = 64 << 20;

  // Throws std::runtime_error naming the file when it cannot be opened.
  explicit LcmLogReader(const std::string& path);
  ~LcmLogReader();
  LcmLogReader(const LcmLogReader&) = delete;
  LcmLogReader& operator=(const LcmLogReader&) = delete;

  // The next complete event whose channel `wanted` accepts (all when empty); false at the end of
  // what is written so far (call again later to follow a growing file).
  bool next(LcmLogEvent& ev, const std::function<bool(const std::string&)>& wanted = {});

  const std::string& path() const { return path_; }
  const LcmLogCounts& counts() const { return counts_; }

 private:
  bool readAt(long offset, void* buf, std::size_t n);
  long fileSize();

  std::string path_;
  std::FILE* f_ = nullptr;
  long offset_ = 0;  // start of the next unread event
  LcmLogCounts counts_;
};

// Appends one event to `f` (lcm-logger's layout); false when the write failed.
bool writeLcmLogEvent(std::FILE* f, const LcmLogEvent& ev);

}  // namespace slide::io
