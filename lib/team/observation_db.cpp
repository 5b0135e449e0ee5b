#include "team/observation_db.h"

#include <cmath>
#include <stdexcept>

namespace slide::team {

ObservationDb::ObservationDb(const std::string& journal_path) {
  if (journal_path.empty()) return;
  std::vector<JournalRecord> records;
  journal_ = std::make_unique<Journal>(journal_path, &records, &recovery_);
  replayRecords(records, [this](const JournalRecord& r) { return apply(r); }, recovery_);
}

std::string ObservationDb::apply(const JournalRecord& r) {
  ByteReader in(r.payload);
  const std::int64_t origin = in.svarint(), seq = in.svarint();
  if (in.ok() && (origin < INT32_MIN || origin > INT32_MAX || seq < INT32_MIN || seq > INT32_MAX))
    in.fail("origin or seq out of range");
  const auto o = static_cast<std::int32_t>(origin), q = static_cast<std::int32_t>(seq);
  if (r.type == kBundle || r.type == kReceived) {
    Entry e;
    e.first = in.u8() != 0;
    e.step_m = in.f32();
    if (in.ok() && !(std::isfinite(e.step_m) && e.step_m >= 0)) in.fail("step length not finite and >= 0");
    if (r.type == kReceived) {
      e.received = true;
      const std::uint64_t n = in.varint();
      if (in.ok() && n > in.remaining()) in.fail("tag length out of range");
      for (std::uint64_t k = 0; in.ok() && k < n; ++k) e.tags.push_back(in.u8());
    }
    if (!in.ok()) return "bad bundle record: " + in.error();
    if (absent(o, q)) return "bundle " + std::to_string(o) + "/" + std::to_string(q) + " was declared absent";
    e.data.assign(r.payload.begin() + static_cast<std::ptrdiff_t>(in.position()), r.payload.end());
    if (!has(o, q)) insert(o, q, std::move(e));
  } else if (r.type == kDelivered) {
    if (!in.ok()) return "bad delivery record: " + in.error();
    delivered_[o].insert(q);
  } else if (r.type == kAbsent) {
    const std::int64_t last = in.svarint();
    if (in.ok() && (last < seq || last > INT32_MAX)) in.fail("range end out of range");
    if (!in.ok()) return "bad absence record: " + in.error();
    const SeqRange range{q, static_cast<std::int32_t>(last)};
    auto held = stored_.find(o);
    if (held != stored_.end() && held->second.intersects(range))
      return "absence of " + std::to_string(o) + "/" + std::to_string(q) + ".." + std::to_string(last) +
             " contradicts a held bundle";
    absent_[o].insert(range);
    held_[o].insert(range);
  }
  // Unknown record types are skipped: a newer version may add some.
  return {};
}

void ObservationDb::insert(std::int32_t origin, std::int32_t seq, Entry entry) {
  if (entry.first && !first_.count(origin)) first_[origin] = seq;
  metres_[origin] += entry.step_m;
  held_[origin].insert(seq);
  stored_[origin].insert(seq);
  entries_.emplace(std::make_pair(origin, seq), std::move(entry));
}

bool ObservationDb::addAbsent(std::int32_t origin, std::int32_t first, std::int32_t last) {
  if (first > last) return false;
  auto held = held_.find(origin);
  if (held != held_.end() && held->second.intersects({first, last})) return false;
  ByteWriter w;
  w.svarint(origin);
  w.svarint(first);
  w.svarint(last);
  if (!journal(kAbsent, w.data())) return false;
  absent_[origin].insert(SeqRange{first, last});
  held_[origin].insert(SeqRange{first, last});
  return true;
}

bool ObservationDb::absentAll(std::int32_t origin, SeqRange r) const {
  auto it = absent_.find(origin);
  return it != absent_.end() && RangeSet::fromRanges({r}).minus(it->second, 1).empty();
}

bool ObservationDb::absent(std::int32_t origin, std::int32_t seq) const {
  auto it = absent_.find(origin);
  return it != absent_.end() && it->second.contains(seq);
}

bool ObservationDb::has(std::int32_t origin, std::int32_t seq) const { return entries_.count({origin, seq}) > 0; }

const ObservationDb::Entry* ObservationDb::get(std::int32_t origin, std::int32_t seq) const {
  auto it = entries_.find({origin, seq});
  return it == entries_.end() ? nullptr : &it->second;
}

bool ObservationDb::add(std::int32_t origin, std::int32_t seq, Entry entry) {
  if (has(origin, seq)) return false;
  ByteWriter w;
  w.svarint(origin);
  w.svarint(seq);
  w.u8(entry.first ? 1 : 0);
  w.f32(entry.step_m);
  if (entry.received) {
    w.varint(entry.tags.size());
    w.bytes(entry.tags.data(), entry.tags.size());
  }
  w.bytes(entry.data.data(), entry.data.size());
  if (!journal(entry.received ? kReceived : kBundle, w.data())) return false;
  insert(origin, seq, std::move(entry));
  return true;
}

std::optional<std::int32_t> ObservationDb::firstSeq(std::int32_t origin) const {
  auto it = first_.find(origin);
  if (it == first_.end()) return std::nullopt;
  return it->second;
}

double ObservationDb::metres(std::int32_t origin) const {
  auto it = metres_.find(origin);
  return it == metres_.end() ? 0.0 : it->second;
}

std::size_t ObservationDb::size() const { return entries_.size(); }

std::optional<std::pair<std::int32_t, std::int32_t>> ObservationDb::nextToDeliver(std::int32_t skip) const {
  for (const auto& [origin, first] : first_) {
    if (origin == skip) continue;
    auto d = delivered_.find(origin);
    std::int64_t next = (d == delivered_.end() || d->second.empty()) ? first : std::int64_t{d->second.max()} + 1;
    // Absent seqs are stepped over (ranges are merged, so one step suffices).
    auto a = absent_.find(origin);
    if (a != absent_.end() && next <= INT32_MAX)
      if (const auto r = a->second.rangeOf(static_cast<std::int32_t>(next))) next = std::int64_t{r->last} + 1;
    if (next <= INT32_MAX && has(origin, static_cast<std::int32_t>(next)))
      return std::make_pair(origin, static_cast<std::int32_t>(next));
  }
  return std::nullopt;
}

void ObservationDb::markDelivered(std::int32_t origin, std::int32_t seq) {
  if (delivered(origin, seq)) return;
  ByteWriter w;
  w.svarint(origin);
  w.svarint(seq);
  journal(kDelivered, w.data());  // recorded in memory all the same: no delivery loop on a full disk
  delivered_[origin].insert(seq);
}

bool ObservationDb::journal(std::uint8_t type, const Bytes& payload) {
  if (!journal_) return true;
  try {
    journal_->append(type, payload);
    return true;
  } catch (const std::runtime_error& e) {
    ++journal_failures_;
    journal_error_ = e.what();
    return false;
  }
}

bool ObservationDb::delivered(std::int32_t origin, std::int32_t seq) const {
  auto it = delivered_.find(origin);
  return it != delivered_.end() && it->second.contains(seq);
}

}  // namespace slide::team
