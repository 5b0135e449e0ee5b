#pragma once
// Sets of bundle sequence numbers kept as sorted, disjoint, non-adjacent inclusive ranges,
// and the per-origin map of such sets that heartbeats and acknowledgements carry.
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

namespace slide::team {

struct SeqRange {
  std::int32_t first = 0;
  std::int32_t last = 0;  // inclusive
  bool operator==(const SeqRange& o) const { return first == o.first && last == o.last; }
};

class RangeSet {
 public:
  RangeSet() = default;
  // Builds from any list of ranges (overlapping or unsorted are merged); first > last is skipped.
  static RangeSet fromRanges(const std::vector<SeqRange>& ranges);

  bool insert(std::int32_t seq);  // true when seq was new
  void insert(SeqRange r);
  void insert(const RangeSet& other);
  bool contains(std::int32_t seq) const;
  bool intersects(SeqRange r) const;  // some seq of r (first <= last) is in the set
  // The range holding seq, if any.
  std::optional<SeqRange> rangeOf(std::int32_t seq) const;
  bool empty() const { return ranges_.empty(); }
  std::int64_t count() const;
  std::int32_t max() const { return ranges_.rbegin()->second; }  // requires !empty()
  std::int32_t min() const { return ranges_.begin()->first; }    // requires !empty()

  // Ranges in ascending order.
  std::vector<SeqRange> ranges() const;
  // Sequence numbers in this set and not in `other`, ascending, at most `limit` of them.
  std::vector<std::int32_t> minus(const RangeSet& other, std::size_t limit) const;
  bool operator==(const RangeSet& o) const { return ranges_ == o.ranges_; }

 private:
  std::map<std::int32_t, std::int32_t> ranges_;  // first -> last
};

// Per origin robot, the sequence numbers held (or acknowledged).
using OriginRanges = std::map<std::int32_t, RangeSet>;

void insertAll(OriginRanges& into, const OriginRanges& from);

}  // namespace slide::team
