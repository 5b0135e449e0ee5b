#pragma once
// The observation database: encoded bundles by (origin, seq), own and received, journalled
// before they count as held, plus the per-origin delivery cursor (journalled on each
// delivery) so that a restarted daemon neither repeats nor skips a delivery. Nothing stored is
// ever replaced. Sequence numbers an origin declared absent (own bundles lost before they
// reached peer sync) count as held, carry no data and are skipped by delivery. Journal records
// that cannot be used are skipped and counted (recovery().skipped), never fatal. A journal
// write that fails (a full disk) is counted (journalFailures), never thrown: a bundle or
// absence is then not taken (it comes again from a peer, or the gap is bridged later); a
// delivery is recorded in memory only (after a restart it is delivered once more).
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "team/journal.h"
#include "team/seq_ranges.h"

namespace slide::team {

class ObservationDb {
 public:
  struct Entry {
    Bytes data;           // compact encoding (codec.h)
    bool first = false;   // first bundle of its origin
    float step_m = 0;     // length of its relative odometry (for per-metre accounting)
    bool received = false;  // from a peer (not this robot's own input)
    Bytes tags;           // its origin's tags (message_auth.h), forwarded when relayed
  };

  // Rebuilds from the journal at `journal_path` (created if missing; empty path: memory only).
  explicit ObservationDb(const std::string& journal_path);

  bool has(std::int32_t origin, std::int32_t seq) const;
  const Entry* get(std::int32_t origin, std::int32_t seq) const;
  // Stores and journals a new bundle; false (and nothing changes) when it is already held or
  // the journal write failed.
  bool add(std::int32_t origin, std::int32_t seq, Entry entry);
  // Journals that seqs first..last of `origin` do not exist (none of them held); false (and
  // nothing changes) when one of them is held, the range is empty or the journal write failed.
  bool addAbsent(std::int32_t origin, std::int32_t first, std::int32_t last);
  bool absent(std::int32_t origin, std::int32_t seq) const;
  bool absentAll(std::int32_t origin, SeqRange r) const;  // every seq of r is absent
  // Bundles and absent seqs; bundles only.
  const OriginRanges& held() const { return held_; }
  const OriginRanges& stored() const { return stored_; }
  std::optional<std::int32_t> firstSeq(std::int32_t origin) const;
  double metres(std::int32_t origin) const;
  std::size_t size() const;

  // The next bundle in per-origin order not yet delivered, over origins other than `skip`.
  std::optional<std::pair<std::int32_t, std::int32_t>> nextToDeliver(std::int32_t skip) const;
  void markDelivered(std::int32_t origin, std::int32_t seq);
  bool delivered(std::int32_t origin, std::int32_t seq) const;
  const JournalRecovery& recovery() const { return recovery_; }
  std::uint64_t journalFailures() const { return journal_failures_; }
  const std::string& lastJournalError() const { return journal_error_; }

 private:
  // kBundle: own input; kReceived: from a peer, with its origin's tags.
  enum RecordType : std::uint8_t { kBundle = 1, kDelivered = 2, kAbsent = 3, kReceived = 4 };
  // Empty when the record was used, else why it was skipped.
  std::string apply(const JournalRecord& r);
  bool journal(std::uint8_t type, const Bytes& payload);  // false (and counted) when the write failed
  void insert(std::int32_t origin, std::int32_t seq, Entry entry);

  std::map<std::pair<std::int32_t, std::int32_t>, Entry> entries_;
  OriginRanges held_;
  OriginRanges absent_;
  OriginRanges stored_;
  OriginRanges delivered_;
  std::map<std::int32_t, std::int32_t> first_;
  std::map<std::int32_t, double> metres_;
  std::unique_ptr<Journal> journal_;
  JournalRecovery recovery_;
  std::uint64_t journal_failures_ = 0;
  std::string journal_error_;
};

}  // namespace slide::team
