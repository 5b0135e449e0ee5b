#pragma once
// An append-only file of checksummed records that survives kill -9 at any instant: each
// record goes out in one write(), and on opening, a damaged or truncated tail is detected,
// saved aside (<path>.damaged-<offset>) and cut off, so appends continue after the last good
// record. Record: magic "SJ1\n", type u8, length u32, payload, CRC-32 of type+length+payload.
#include <cstdint>
#include <string>
#include <vector>

#include "team/byte_io.h"

namespace slide::team {

struct JournalRecord {
  std::uint8_t type = 0;
  Bytes payload;
};

struct JournalRecovery {
  std::size_t records = 0;        // good records read
  std::size_t good_bytes = 0;     // file length kept
  std::size_t dropped_bytes = 0;  // damaged tail cut off (0 when the file was clean)
  std::string damaged_copy;       // where the damaged tail was saved, if any
  std::size_t skipped = 0;        // intact records the reader could not use (and skipped)
  std::string first_skipped;      // why the first of them was skipped
};

class Journal {
 public:
  static constexpr std::size_t kMaxPayload = 16 << 20;

  // Opens or creates `path`, returns every good record in `records`; throws std::runtime_error
  // naming the path when it cannot be opened or repaired.
  Journal(const std::string& path, std::vector<JournalRecord>* records, JournalRecovery* recovery = nullptr);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  // Appends one record (one write() call); `sync` adds fdatasync for power-loss safety.
  void append(std::uint8_t type, const Bytes& payload, bool sync = false);
  const std::string& path() const { return path_; }

  static Bytes frame(std::uint8_t type, const Bytes& payload);

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace slide::team
