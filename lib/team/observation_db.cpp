#include "team/observation_db.h"

#include <stdexcept>

namespace slide::team {

ObservationDb::ObservationDb(const std::string& journal_path) {
  if (journal_path.empty()) return;
  std::vector<JournalRecord> records;
  journal_ = std::make_unique<Journal>(journal_path, &records, &recovery_);
  for (const auto& r : records) apply(r);
}

void ObservationDb::apply(const JournalRecord& r) {
  ByteReader in(r.payload);
  const auto origin = static_cast<std::int32_t>(in.svarint());
  const auto seq = static_cast<std::int32_t>(in.svarint());
  if (r.type == kBundle) {
    Entry e;
    e.first = in.u8() != 0;
    e.step_m = in.f32();
    if (!in.ok()) throw std::runtime_error("journal " + journal_->path() + ": bad bundle record: " + in.error());
    e.data.assign(r.payload.begin() + static_cast<std::ptrdiff_t>(in.position()), r.payload.end());
    if (!has(origin, seq)) insert(origin, seq, std::move(e));
  } else if (r.type == kDelivered) {
    if (!in.ok()) throw std::runtime_error("journal " + journal_->path() + ": bad delivery record: " + in.error());
    delivered_[origin].insert(seq);
  }
  // Unknown record types are skipped: a newer version may add some.
}

void ObservationDb::insert(std::int32_t origin, std::int32_t seq, Entry entry) {
  if (entry.first && !first_.count(origin)) first_[origin] = seq;
  metres_[origin] += entry.step_m;
  held_[origin].insert(seq);
  entries_.emplace(std::make_pair(origin, seq), std::move(entry));
}

bool ObservationDb::has(std::int32_t origin, std::int32_t seq) const { return entries_.count({origin, seq}) > 0; }

const ObservationDb::Entry* ObservationDb::get(std::int32_t origin, std::int32_t seq) const {
  auto it = entries_.find({origin, seq});
  return it == entries_.end() ? nullptr : &it->second;
}

bool ObservationDb::add(std::int32_t origin, std::int32_t seq, Entry entry) {
  if (has(origin, seq)) return false;
  if (journal_) {
    ByteWriter w;
    w.svarint(origin);
    w.svarint(seq);
    w.u8(entry.first ? 1 : 0);
    w.f32(entry.step_m);
    w.bytes(entry.data.data(), entry.data.size());
    journal_->append(kBundle, w.data());
  }
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
    const std::int32_t next = (d == delivered_.end() || d->second.empty()) ? first : d->second.max() + 1;
    if (has(origin, next)) return std::make_pair(origin, next);
  }
  return std::nullopt;
}

void ObservationDb::markDelivered(std::int32_t origin, std::int32_t seq) {
  if (delivered(origin, seq)) return;
  if (journal_) {
    ByteWriter w;
    w.svarint(origin);
    w.svarint(seq);
    journal_->append(kDelivered, w.data());
  }
  delivered_[origin].insert(seq);
}

bool ObservationDb::delivered(std::int32_t origin, std::int32_t seq) const {
  auto it = delivered_.find(origin);
  return it != delivered_.end() && it->second.contains(seq);
}

}  // namespace slide::team
