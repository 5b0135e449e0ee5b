#pragma once
// An append-only file of checksummed records that survives kill -9 at any instant: each
// record goes out in one write(), and on opening, a damaged or truncated tail is detected,
// saved aside (<path>.damaged-<offset>; on a full disk it is not) and cut off, so appends
// continue after the last good record. A failed append (a full disk) is cut back off too, so a torn record never hides the
// records after it. Record: magic "SJ1\n", type u8, length u32, payload, CRC-32 of
// type+length+payload. Used by peer sync (observation_db.h) and the optimizer daemon.
#include <cstdint>
#include <functional>
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
  std::string not_saved;          // why it could not be saved (a full disk): cut all the same
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

  // Appends one record (one write() call); `sync` adds fdatasync for power-loss safety. On a
  // failed write (ENOSPC, EIO) the file is cut back to its last good record and
  // std::runtime_error names the path and the system error.
  void append(std::uint8_t type, const Bytes& payload, bool sync = false);
  const std::string& path() const { return path_; }

  // The good records of `path` without changing the file (for tools): a damaged tail is only
  // reported in `recovery`. A missing file has none; throws when it exists but cannot be read.
  static std::vector<JournalRecord> read(const std::string& path, JournalRecovery* recovery = nullptr);
  // True when the file at `path` starts like a journal (or is empty or missing).
  static bool looksLikeJournal(const std::string& path);

  static Bytes frame(std::uint8_t type, const Bytes& payload);

 private:
  std::string path_;
  int fd_ = -1;
  std::size_t size_ = 0;  // end of the last good record
};

// Replays `records` in order through `apply`, which returns empty when it used the record, else
// why not. A record it rejects or whose replay throws is skipped: counted in
// `recovery.skipped` (the first reason, with the record's number, in first_skipped) while the
// others are still replayed. Returns the records used.
std::size_t replayRecords(const std::vector<JournalRecord>& records,
                          const std::function<std::string(const JournalRecord&)>& apply, JournalRecovery& recovery);

}  // namespace slide::team
