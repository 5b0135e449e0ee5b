#include "team/seq_ranges.h"

#include <algorithm>

namespace slide::team {

RangeSet RangeSet::fromRanges(const std::vector<SeqRange>& ranges) {
  RangeSet s;
  for (const auto& r : ranges) s.insert(r);
  return s;
}

bool RangeSet::insert(std::int32_t seq) {
  if (contains(seq)) return false;
  insert(SeqRange{seq, seq});
  return true;
}

void RangeSet::insert(SeqRange r) {
  if (r.first > r.last) return;
  std::int64_t first = r.first, last = r.last;
  // Merge with every range that overlaps or touches [first, last].
  auto it = ranges_.upper_bound(r.first);
  if (it != ranges_.begin()) {
    auto prev = std::prev(it);
    if (static_cast<std::int64_t>(prev->second) + 1 >= first) it = prev;
  }
  while (it != ranges_.end() && static_cast<std::int64_t>(it->first) <= last + 1) {
    first = std::min<std::int64_t>(first, it->first);
    last = std::max<std::int64_t>(last, it->second);
    it = ranges_.erase(it);
  }
  ranges_.emplace(static_cast<std::int32_t>(first), static_cast<std::int32_t>(last));
}

void RangeSet::insert(const RangeSet& other) {
  for (const auto& [f, l] : other.ranges_) insert(SeqRange{f, l});
}

bool RangeSet::contains(std::int32_t seq) const {
  auto it = ranges_.upper_bound(seq);
  if (it == ranges_.begin()) return false;
  --it;
  return seq <= it->second;
}

bool RangeSet::intersects(SeqRange r) const {
  auto it = ranges_.upper_bound(r.last);  // first range starting after r
  if (it == ranges_.begin()) return false;
  return std::prev(it)->second >= r.first;
}

std::optional<SeqRange> RangeSet::rangeOf(std::int32_t seq) const {
  auto it = ranges_.upper_bound(seq);
  if (it == ranges_.begin()) return std::nullopt;
  --it;
  if (seq > it->second) return std::nullopt;
  return SeqRange{it->first, it->second};
}

std::int64_t RangeSet::count() const {
  std::int64_t n = 0;
  for (const auto& [f, l] : ranges_) n += static_cast<std::int64_t>(l) - f + 1;
  return n;
}

std::vector<SeqRange> RangeSet::ranges() const {
  std::vector<SeqRange> out;
  out.reserve(ranges_.size());
  for (const auto& [f, l] : ranges_) out.push_back({f, l});
  return out;
}

std::vector<std::int32_t> RangeSet::minus(const RangeSet& other, std::size_t limit) const {
  std::vector<std::int32_t> out;
  for (const auto& [f, l] : ranges_) {
    for (std::int64_t s = f; s <= l && out.size() < limit; ++s) {
      const auto seq = static_cast<std::int32_t>(s);
      if (other.contains(seq)) {
        // Skip to the end of the covering range of `other`.
        auto it = other.ranges_.upper_bound(seq);
        --it;
        s = it->second;
        continue;
      }
      out.push_back(seq);
    }
    if (out.size() >= limit) break;
  }
  return out;
}

void insertAll(OriginRanges& into, const OriginRanges& from) {
  for (const auto& [origin, set] : from) into[origin].insert(set);
}

}  // namespace slide::team
